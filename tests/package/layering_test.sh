#!/usr/bin/env bash
# The layering the build enforces (docs/ARCHITECTURE.md, "Layers"): the public headers stand alone
# (include/ and the standard library), and a front end compiled as the build compiles it reaches
# the API and the engine header but no layer's header.
# Usage: layering_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build_dir=$1
source_dir=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# 1. Every public header alone, with include/ as the only path (luz/json.h also needs nlohmann).
for h in "$source_dir"/include/luz/*.h; do
  echo "#include \"luz/$(basename "$h")\"" >"$tmp/probe.cpp"
  g++ -std=c++20 -fsyntax-only -I"$source_dir/include" "$tmp/probe.cpp"
done

# 2. luz/luz.h stays the core a library user needs: the public headers it pulls in, at most
# 850 lines in all (what only some front ends need has its own header, docs/LIBRARY.md).
limit=850
closure=$(echo '#include "luz/luz.h"' | g++ -std=c++20 -I"$source_dir/include" -x c++ -E -H - \
  2>&1 >/dev/null | grep -o 'luz/[a-z_0-9]*\.h$' | sort -u)
lines=$(cd "$source_dir/include" && cat $closure | wc -l)
echo "luz/luz.h pulls in $(echo "$closure" | wc -l) public headers, $lines lines (limit $limit)"
if [ "$lines" -gt "$limit" ]; then
  echo "luz/luz.h's closure is $lines lines, over $limit: give what only some front ends need" \
    "a header of its own" >&2
  exit 1
fi

# 3. The luz command's flags, as the build gives them to app/cli_main.cpp.
flags=$(/usr/bin/python3 - "$build_dir/compile_commands.json" <<'PY'
import json, shlex, sys
for c in json.load(open(sys.argv[1])):
    # app/cli_main.cpp, or the batch that holds it in a unity build (the sanitize preset)
    if c["file"].endswith("src/app/cli_main.cpp") or "/luz_app.dir/Unity/" in c["command"]:
        args = shlex.split(c["command"])
        print(" ".join(shlex.quote(a) for a in args if a.startswith(("-I", "-isystem", "-std"))))
        break
PY
)
test -n "$flags"
compiles() {
  printf '%s\n' "$@" >"$tmp/probe.cpp"
  eval g++ -fsyntax-only $flags "$tmp/probe.cpp" 2>/dev/null
}
compiles '#include "luz/luz.h"' '#include "luz_engine.h"' '#include "app/cli_main.h"'
for internal in render/render.h geometry/scene.h scene/scene_loader.h image/image_io.h \
  api/built_scene.h engine/luz_engine.h; do
  if compiles "#include \"$internal\""; then
    echo "a front end includes $internal: the build should refuse it" >&2
    exit 1
  fi
done
echo "public headers stand alone; the luz command reaches luz/, luz_engine.h and app/ only"
