#!/usr/bin/env bash
# The package test: installs luz into a temporary prefix, builds examples/ against it with
# find_package(luz), and checks that examples/minimal writes the very bytes `luz render` writes.
# Usage: install_test.sh BUILD_DIR SOURCE_DIR [BUILD_TYPE]
set -euo pipefail
build_dir=$1
source_dir=$2
build_type=${3:-Release}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

cmake --install "$build_dir" --prefix "$tmp/prefix" >/dev/null
test -x "$tmp/prefix/bin/luz"
test -f "$tmp/prefix/include/luz/luz.h"
# The public headers alone: no layer's header is installed, and luz.h needs none.
test ! -e "$tmp/prefix/include/luz/internal"
echo '#include <luz/luz.h>' >"$tmp/public.cpp"
g++ -std=c++20 -fsyntax-only -I"$tmp/prefix/include" "$tmp/public.cpp"
test -f "$tmp/prefix/lib/cmake/luz/luzConfig.cmake" ||
  test -f "$tmp"/prefix/lib/*/cmake/luz/luzConfig.cmake
cmake -S "$source_dir/examples" -B "$tmp/build" -G Ninja -DCMAKE_BUILD_TYPE="$build_type" \
  -DCMAKE_PREFIX_PATH="$tmp/prefix" >/dev/null
cmake --build "$tmp/build" >/dev/null
"$tmp/build/minimal" "$tmp/minimal.png"
"$tmp/prefix/bin/luz" render demo:primitives -o "$tmp/cli.png" -q
cmp "$tmp/minimal.png" "$tmp/cli.png"
echo "examples/minimal wrote the same $(stat -c %s "$tmp/cli.png") bytes as luz render"

# The viewer, when it was built, is a module the installed luz finds and loads (luz view); luz
# render does not load SDL2.
if [ -n "$(find "$tmp/prefix" -name luz_viewer.so)" ]; then
  "$tmp/prefix/bin/luz" view demo:primitives --benchmark --width 16 --height 12 --threads 1 |
    grep -q "all passes"
  if ldd "$tmp/prefix/bin/luz" | grep -q SDL2; then
    echo "luz links SDL2: the viewer should be a module" >&2
    exit 1
  fi
  echo "the installed luz loads its viewer module; luz itself does not link SDL2"
fi

# The Python package, when it was built: importable from where it was installed.
for site in "$tmp"/prefix/lib/python3*/site-packages; do
  if [ -d "$site/luz" ]; then
    PYTHONPATH="$site" /usr/bin/python3 -c \
      "import luz; assert luz.render('demo:primitives', width=8, height=6).image.shape == (6, 8, 3)"
    echo "the Python package imports from $site"
  fi
done
