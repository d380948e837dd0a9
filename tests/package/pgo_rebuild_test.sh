#!/usr/bin/env bash
# The profile-guided build compiles again after retraining (cmake/pgo.cmake): every C++ object of
# the profiled targets has the profile's stamp as an input, so that deleting <build>/pgo (a new
# profile) recompiles each of them, not only retrains. Configures a scratch build (no compiling)
# with Ninja and asks Ninja for each object's inputs.
# Usage: pgo_rebuild_test.sh SOURCE_DIR
set -euo pipefail
source_dir=$1
command -v ninja >/dev/null || { echo "ninja not installed: skipped"; exit 77; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cmake -S "$source_dir" -B "$tmp" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=g++ \
  -DLUZ_PGO=ON -DLUZ_LTO=OFF -DLUZ_BUILD_TESTS=OFF -DLUZ_BUILD_PYTHON=OFF -DLUZ_WEB=OFF \
  -DLUZ_BUILD_VIEWER=OFF -DLUZ_BUILD_MPI=OFF -DLUZ_BUILD_BENCH=OFF >"$tmp/configure.log" 2>&1 ||
  { cat "$tmp/configure.log" >&2; exit 1; }
objects=$(ninja -C "$tmp" -t targets all | grep -o '^CMakeFiles/luz[a-z_]*\.dir/[^:]*\.cpp\.o' |
  sort -u)
count=$(echo "$objects" | grep -c . || true)
if [ "$count" -lt 40 ]; then
  echo "found only $count luz objects in the scratch build: the test no longer sees them" >&2
  exit 1
fi
missing=0
for o in $objects; do
  inputs=$(ninja -C "$tmp" -t query "$o")  # (not piped into grep -q: SIGPIPE under pipefail)
  if ! grep -q '^ *| .*pgo/profile\.stamp' <<<"$inputs"; then
    echo "$o: does not depend on pgo/profile.stamp (a new profile would not recompile it)" >&2
    missing=$((missing + 1))
  fi
done
[ "$missing" -eq 0 ] || exit 1
echo "all $count objects of the profiled targets depend on pgo/profile.stamp"
