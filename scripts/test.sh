#!/usr/bin/env bash
# Second command of the README: install what is missing, then build and run every test twice:
# in Release (the `release` preset's -O3 build without its two whole-program optimisations,
# profile-guided training and link-time optimisation: they change how the compiler arranges
# the same code, not what it does — the test programs link the libraries' machine code either
# way — and cost a second build of the libraries and four whole-program links; the libraries
# compiled as unity files, as the sanitizer pass compiles them: a third less compile time),
# and in Debug with AddressSanitizer and UndefinedBehaviorSanitizer (the `sanitize` preset:
# `dev` with line tables only, -g1, without ASan's use-after-scope and UBSan's vptr checks;
# without luz-mpi and the viewer). The Python bindings are compiled at -O1 and the web page at
# -O0 (LUZ_QUICK_BINDINGS).
#   scripts/test.sh                  all of it (CI runs this)
#   scripts/test.sh --release-only   without the sanitizer pass
#   scripts/test.sh --save-costs     keep the last run's test times in tests/ctest_costs/ (for
#                                    the order in which a fresh build folder runs them)
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

if [ "${1:-}" = "--save-costs" ]; then  # the test times of the last run, for seed_costs below
  for preset in release sanitize; do
    /usr/bin/python3 - "build/$preset/Testing/Temporary/CTestCostData.txt" \
      "tests/ctest_costs/$preset.txt" <<'PY'
import re, sys
rows = []
for line in open(sys.argv[1]):
    if line.startswith("---"):
        break
    name, _, cost = (line.rstrip("\n").split(" ") + ["", "", ""])[:3]
    if re.fullmatch(r"[\w./:-]+", name) and re.fullmatch(r"[\d.]+", cost) and float(cost) >= 0.3:
        rows.append((float(cost), name))
open(sys.argv[2], "w").write("".join(f"{n} 1 {c:.2f}\n" for c, n in sorted(rows, reverse=True)))
PY
  done
  exit
fi

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
sanitize=1
[ "${1:-}" != "--release-only" ] || sanitize=0

# ctest starts the longest tests first when it knows their times: a fresh build folder gets
# those of an earlier run (tests/ctest_costs/, refreshed by `scripts/test.sh --save-costs`).
seed_costs() {
  local dir="build/$1/Testing/Temporary"
  [ -f "tests/ctest_costs/$1.txt" ] && [ ! -f "$dir/CTestCostData.txt" ] || return 0
  mkdir -p "$dir" && cp "tests/ctest_costs/$1.txt" "$dir/CTestCostData.txt"
}

cmake --preset release -DLUZ_PGO=OFF -DLUZ_LTO=OFF -DCMAKE_UNITY_BUILD=ON \
  -DLUZ_QUICK_BINDINGS=ON >/dev/null
step "Release build" cmake --build --preset release
seed_costs release
step "Release tests" ctest --preset release -j "$jobs"

if ((sanitize)); then
  # Without luz-mpi and the viewer: their tests wait on processes and a display, one test at a
  # time (RUN_SERIAL), two minutes of the pass; the Release pass runs them.
  cmake --preset sanitize -DLUZ_BUILD_MPI=OFF -DLUZ_BUILD_VIEWER=OFF >/dev/null
  step "Debug build with ASan + UBSan" cmake --build --preset sanitize
  seed_costs sanitize
  step "Sanitizer tests" env ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 \
    UBSAN_OPTIONS=print_stacktrace=1 ctest --preset sanitize -j "$jobs"
fi
echo "== scripts/test.sh: $((SECONDS - begin)) s"
