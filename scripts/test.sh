#!/usr/bin/env bash
# Second command of the README: install what is missing, then build and run every test twice:
# in Release, and in Debug with AddressSanitizer and UndefinedBehaviorSanitizer (the `dev`
# preset). `scripts/test.sh --release-only` skips the sanitizer pass.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
jobs="$(nproc)"

echo "== Release build and tests"
cmake --preset release >/dev/null
cmake --build --preset release
ctest --preset release -j "$jobs"

if [ "${1:-}" != "--release-only" ]; then
  echo "== Debug build with ASan + UBSan, and tests"
  cmake --preset dev >/dev/null
  cmake --build --preset dev
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
    ctest --preset dev -j "$jobs"
fi
