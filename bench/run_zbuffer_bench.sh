#!/usr/bin/env bash
# Runs the zbuffer-vs-llvmpipe benchmark (docs/BENCHMARKS.md): installs the Debian packages it
# needs, configures and builds the `native` preset, runs it and prints the table.
#
# usage: bench/run_zbuffer_bench.sh [--profile] [--no-wait] [BENCHMARK OPTIONS...]
#   --profile   also split luz's frame time into phases with perf (1 thread, every size)
#   --no-wait   do not wait for other processes to leave the CPUs idle before each run
#   BENCHMARK OPTIONS go to zbuffer_vs_llvmpipe (e.g. --sizes 5k,100k --frames 20; --help)
set -euo pipefail

repo=$(cd "$(dirname "$0")/.." && pwd)
command="bench/run_zbuffer_bench.sh $*"
profile=0
wait_idle=1
args=()
for a in "$@"; do
    case "$a" in
        --profile) profile=1 ;;
        --no-wait) wait_idle=0 ;;
        *) args+=("$a") ;;
    esac
done

# 1. Debian packages: the project's build dependencies, OSMesa (llvmpipe) and, for --profile,
#    perf and python3.
packages=(cmake ninja-build g++ pkg-config nlohmann-json3-dev libcli11-dev libpng-dev
          libopenexr-dev libtbb-dev libgtest-dev libgmock-dev libosmesa6-dev libgl1-mesa-dri)
if ((profile)); then packages+=(linux-perf python3 binutils); fi
"$repo/bench/install_packages.sh" "${packages[@]}"

# 2. Configure and build the `native` preset (Release, -march=native, benchmarks on).
cd "$repo"
cmake --preset native >/dev/null
cmake --build build/native --target zbuffer_vs_llvmpipe
bench=build/native/bench/zbuffer_vs_llvmpipe

# 3. The benchmark waits, before every run, until other processes leave the CPUs idle (the
#    comparison is of wall times on a 2-core machine), and repeats a run they disturbed.
if ((!wait_idle)); then args=(--idle-wait 0 "${args[@]}"); fi

# 4. The benchmark; the table also goes to build/native/zbuffer_vs_llvmpipe.txt.
{
    echo "# $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) CPUs: $(lscpu | sed -n 's/^Model name: *//p')"
    echo "# command: $command"
    "$bench" "${args[@]}"
} | tee build/native/zbuffer_vs_llvmpipe.txt

# 5. Optional: where luz's frame time goes, from perf samples (needs a -g build: a separate
#    build directory with the same preset, so build/native's flags stay as the preset says).
if ((profile)); then
    cmake --preset native -B build/native-prof -DCMAKE_CXX_FLAGS=-g >/dev/null
    cmake --build build/native-prof --target zbuffer_vs_llvmpipe
    for level in 72 316 1000; do
        echo
        echo "== luz phases, torus level $level, 1 thread (perf, cpu-clock samples) =="
        data=$(mktemp /tmp/luz_zbuffer_perf.XXXXXX)
        frames=$((level < 500 ? 60 : 15))
        perf record -q -e cpu-clock -F 1000 --call-graph dwarf -o "$data" \
            build/native-prof/bench/zbuffer_vs_llvmpipe --profile "$level" --threads 1 \
            --frames "$frames" >/dev/null 2>&1
        python3 bench/zbuffer_phases.py "$data" \
            src/render/zbuffer.cpp,src/render/rasterizer.cpp,src/render/zbuffer_shade.h 12
        rm -f "$data" "$data.old"
    done
fi
