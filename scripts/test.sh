#!/usr/bin/env bash
# Second command of the README: install what is missing, then build and run every test twice:
# in Release with LTO (the `ci` preset), and in Debug with AddressSanitizer and
# UndefinedBehaviorSanitizer (the `sanitize` preset: `dev` with line tables only). Between the
# two, the `release` preset's luz (PGO + LTO) is built alone and must write the same bytes as the
# tested luz for every golden case (tests/golden/cases.txt): PGO changes speed, never pixels.
#   scripts/test.sh                  all of it (CI runs this)
#   scripts/test.sh --release-only   without the sanitizer pass
#   scripts/test.sh --quick [BUILD]  the tests not labelled `slow`, in a build folder that has
#                                    the tests (default: build/ci, build/fast, build/release or
#                                    build/dev), after an incremental build: under 3 minutes
set -euo pipefail
cd "$(dirname "$0")/.."
jobs="$(nproc)"
step() {  # step NAME COMMAND…: runs it, then says how long it took
  local start=$SECONDS
  "${@:2}"
  echo "== $1: $((SECONDS - start)) s"
}

if [ "${1:-}" = "--quick" ]; then
  build="${2:-}"
  for b in build/ci build/fast build/release build/dev; do
    [ -n "$build" ] || [ ! -f "$b/CTestTestfile.cmake" ] || build="$b"
  done
  if [ -z "$build" ] || [ ! -f "$build/CTestTestfile.cmake" ]; then
    echo "scripts/test.sh --quick: no build folder with the tests (cmake --preset ci first)" >&2
    exit 2
  fi
  cmake --build "$build"
  exec ctest --test-dir "$build" --label-exclude slow -j "$jobs" --output-on-failure
fi

scripts/setup.sh

# Every golden case rendered by luz binaries $1 and $2 into PFM (exact floats): the same bytes.
same_images() {
  local dir
  dir="$(mktemp -d)"
  local n=0
  while read -r name args; do
    [ -z "$name" ] || [ "${name:0:1}" = "#" ] && continue
    # shellcheck disable=SC2086  # the arguments are split at blanks, as golden_test.cpp does
    "$1" $args -o "$dir/$name.a.pfm"
    # shellcheck disable=SC2086
    "$2" $args -o "$dir/$name.b.pfm"
    cmp "$dir/$name.a.pfm" "$dir/$name.b.pfm"
    n=$((n + 1))
  done < tests/golden/cases.txt
  rm -rf "$dir"
  echo "$n golden cases: the same bytes from $1 and $2"
}

cmake --preset ci >/dev/null
step "Release build (LTO, no PGO)" cmake --build --preset ci
step "Release tests" ctest --preset ci -j "$jobs"

cmake --preset pgo-smoke >/dev/null
step "PGO build of luz (the release preset's)" cmake --build --preset pgo-smoke
step "PGO luz against the tested luz" same_images build/pgo-smoke/luz build/ci/luz

if [ "${1:-}" != "--release-only" ]; then
  cmake --preset sanitize >/dev/null
  step "Debug build with ASan + UBSan" cmake --build --preset sanitize
  step "Sanitizer tests" env ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 \
    UBSAN_OPTIONS=print_stacktrace=1 ctest --preset sanitize -j "$jobs"
fi
