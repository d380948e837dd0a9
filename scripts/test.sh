#!/usr/bin/env bash
# Second command of the README: install what is missing, then build and run every test twice:
# in Release (the `release` preset's -O3 build without its two whole-program optimisations,
# profile-guided training and link-time optimisation: they change how the compiler arranges
# the same code, not what it does — the test programs link the libraries' machine code either
# way — and cost a second build of the libraries and four whole-program links), and in Debug
# with AddressSanitizer and UndefinedBehaviorSanitizer (the `sanitize` preset: `dev` with line
# tables only, -g1).
#   scripts/test.sh                  all of it (CI runs this)
#   scripts/test.sh --release-only   without the sanitizer pass
#   scripts/test.sh --quick [BUILD]  the tests not labelled `slow`, in a build folder that has
#                                    the tests (default: the first of build/release, build/fast,
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
  for b in build/release build/fast build/dev; do
    [ -n "$build" ] || [ ! -f "$b/CTestTestfile.cmake" ] || build="$b"
  done
  if [ -z "$build" ] || [ ! -f "$build/CTestTestfile.cmake" ]; then
    echo "scripts/test.sh --quick: no build folder with the tests (cmake --preset release first)" >&2
    exit 2
  fi
  cmake --build "$build"
  exec ctest --test-dir "$build" --label-exclude slow -j "$jobs" --output-on-failure
fi

scripts/setup.sh
begin=$SECONDS

cmake --preset release -DLUZ_PGO=OFF -DLUZ_LTO=OFF >/dev/null
step "Release build" cmake --build --preset release
step "Release tests" ctest --preset release -j "$jobs"

if [ "${1:-}" != "--release-only" ]; then
  cmake --preset sanitize >/dev/null
  step "Debug build with ASan + UBSan" cmake --build --preset sanitize
  step "Sanitizer tests" env ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 \
    UBSAN_OPTIONS=print_stacktrace=1 ctest --preset sanitize -j "$jobs"
fi
echo "== scripts/test.sh: $((SECONDS - begin)) s"
