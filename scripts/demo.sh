#!/usr/bin/env bash
# First command of the README: install what is missing, build in Release, render demo:primitives.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --preset release >/dev/null
cmake --build --preset release
out="${1:-primitives.png}"
build/release/luz render demo:primitives -o "$out"
echo "The practical assignment is in $(realpath "$out")"
