#!/usr/bin/env bash
# Fuzzes the scene loader, the NFF reader, the OBJ/MTL loader and the --checkpoint reader with libFuzzer (clang,
# ASan + UBSan), all at once, for SECONDS each (default 600). Builds into build/fuzz/, seeds from
# scenes/, the demo scenes and tests/corpus/; inputs that fail go to fuzz/findings/<target>/.
#   bash scripts/fuzz.sh [SECONDS] [scene|nff|obj|checkpoint ...]
# Each input a fuzzer found a bug with belongs in tests/corpus/ as a regression case.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-600}"
shift || true
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(scene nff obj checkpoint)

# clang and its libFuzzer runtime (Debian 12: clang, libclang-rt-14-dev), installed if missing
scripts/setup.sh
for p in clang libclang-rt-14-dev; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    sudo=""; [ "$(id -u)" -eq 0 ] || sudo="sudo"
    $sudo apt-get update -qq && DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "$p" >/dev/null
  fi
done
out=build/fuzz
mkdir -p "$out/obj" fuzz/findings
flags=(-std=c++20 -g -O1 -fno-omit-frame-pointer -fno-math-errno
       -fsanitize=address,undefined -fno-sanitize-recover=undefined -Isrc)

# 1. The scene layer, tinyobjloader and the checkpoint reader, instrumented for coverage (fuzzer-no-link).
objs=()
for src in src/scene/*.cpp fuzz/tinyobj_impl.cpp src/render/checkpoint_file.cpp; do
  o="$out/obj/$(basename "${src%.cpp}").o"
  if [ ! -f "$o" ] || [ -n "$(find "$src" src/scene src/math src/render/checkpoint_file.h -newer "$o" \( -name '*.h' -o -path "$src" \))" ]; then
    clang++ "${flags[@]}" -fsanitize=fuzzer-no-link -DLUZ_SCENES_DIR="\"$PWD/scenes\"" -c "$src" -o "$o" &
  fi
  objs+=("$o")
done
wait
for t in scene nff obj checkpoint; do
  clang++ "${flags[@]}" -fsanitize=fuzzer "fuzz/fuzz_${t}_loader.cpp" "${objs[@]}" -lz \
    -o "$out/fuzz_${t}_loader"
done

# 2. Seed corpora (fuzz/corpus/<target>/ keeps what the fuzzer learns between runs).
mkdir -p fuzz/corpus/scene fuzz/corpus/nff fuzz/corpus/obj fuzz/corpus/checkpoint
python3 - <<'PY'
import re, pathlib, hashlib
src = pathlib.Path("src/scene/demo_scenes.cpp").read_text()
for i, text in enumerate(re.findall(r'R"json\((.*?)\)json"', src, re.S)):
    pathlib.Path(f"fuzz/corpus/scene/demo_{i}.json").write_text(text)
PY
seed_scene=(fuzz/corpus/scene)
seed_obj=(fuzz/corpus/obj)
seed_nff=(fuzz/corpus/nff tests/corpus/nff tests/scenes/nff)
seed_checkpoint=(fuzz/corpus/checkpoint tests/corpus/checkpoints)
for d in tests/corpus/scenes fuzz/seeds/scene; do [ -d "$d" ] && seed_scene+=("$d"); done
for d in tests/corpus/obj fuzz/seeds/obj; do [ -d "$d" ] && seed_obj+=("$d"); done
cp -f scenes/*.json fuzz/corpus/scene/ 2>/dev/null || true
# bunny.obj is large: its first 200 lines are seed enough
head -n 200 scenes/bunny.obj > fuzz/corpus/obj/bunny_head.obj
# the SPD scenes are large: their first 300 lines (gears' first 144-gons among them)
for f in scenes/spd/*.nff; do head -n 300 "$f" > "fuzz/corpus/nff/$(basename "$f")"; done

# 3. Run the targets side by side, in fork mode: a bug is written to fuzz/findings/<target>/
#    and fuzzing goes on until the time is up.
run() {
  local t="$1"; shift
  local dir="fuzz/findings/$t"; mkdir -p "$dir"
  ASAN_OPTIONS=detect_leaks=1 \
  "$out/fuzz_${t}_loader" -fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1 \
    -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=65536 \
    -artifact_prefix="$dir/" "$@" >"$dir/log.txt" 2>&1 || true
  echo "== $t: $(grep -E '^#[0-9]+' "$dir/log.txt" | tail -n 1)"
}
for t in "${targets[@]}"; do
  case "$t" in
    scene) run scene -dict=fuzz/json.dict "${seed_scene[@]}" & ;;
    nff) run nff -dict=fuzz/nff.dict "${seed_nff[@]}" & ;;
    obj) run obj -dict=fuzz/obj.dict "${seed_obj[@]}" & ;;
    checkpoint) run checkpoint "${seed_checkpoint[@]}" & ;;
    *) echo "fuzz.sh: unknown target $t (scene, nff, obj or checkpoint)" >&2; exit 2 ;;
  esac
done
wait
ls fuzz/findings/*/ | grep -E "crash-|leak-|timeout-|oom-" || echo "fuzz.sh: no findings"
