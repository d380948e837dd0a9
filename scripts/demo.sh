#!/usr/bin/env bash
# First command of the README: install what is missing, build `luz` alone (the `demo` preset:
# Release without tests, PGO, LTO or the web page; only the packages it needs) and render the practical assignment, demo:primitives.
# The optimised build of everything is `cmake --preset release` (docs/BUILDING.md).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh --demo
start=$SECONDS
cmake --preset demo >/dev/null
cmake --build --preset demo
out="${1:-primitives.png}"
build/demo/luz render demo:primitives -o "$out"
echo "The practical assignment is in $(realpath "$out") (built and rendered in $((SECONDS - start)) s)"
# In the viewer too when there is a display and a build that has it (it is not built here).
for viewer in build/release build/native build/ci; do
  if [ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ] && [ -x "$viewer/luz" ] &&
     [ -e "$viewer/luz_viewer.so" ]; then
    echo "Opening it in $viewer/luz view (close the window to end)"
    exec "$viewer/luz" view demo:primitives
  fi
done
