#!/usr/bin/env bash
# Runs the BVH-vs-Embree benchmark (docs/BENCHMARKS.md, "BVH vs Embree"): installs the Debian
# packages it needs (Embree 3: libembree-dev), configures and builds the `native` preset, writes
# the ≥ 1M-triangle mesh with scripts/make_big_mesh.py, runs both meshes and prints the tables.
#
# usage: bench/run_bvh_bench.sh [--build-dir DIR] [--big-mesh PATH] [BENCHMARK OPTIONS...]
#   --build-dir DIR   build there with the native preset's settings (default build/native)
#   --big-mesh PATH   where the big mesh goes (default /tmp/luz_bigmesh.obj; reused if present)
#   BENCHMARK OPTIONS go to bvh_vs_embree (e.g. --reps 9 --threads 1,2 --scene; --help)
set -euo pipefail

repo=$(cd "$(dirname "$0")/.." && pwd)
command="bench/run_bvh_bench.sh $*"
build_dir=build/native
big=/tmp/luz_bigmesh.obj
args=()
while (($#)); do
    case "$1" in
        --build-dir) build_dir=$2; shift ;;
        --big-mesh) big=$2; shift ;;
        *) args+=("$1") ;;
    esac
    shift
done

# 1. Debian packages: the project's build dependencies, Embree 3 and python3 (the big mesh).
packages=(cmake ninja-build g++ pkg-config nlohmann-json3-dev libcli11-dev libpng-dev
          libopenexr-dev libtbb-dev libgtest-dev libgmock-dev libtinyobjloader-dev
          libembree-dev python3)
"$repo/bench/install_packages.sh" "${packages[@]}"

# 2. Configure and build with the `native` preset (Release, -march=native, benchmarks on).
cd "$repo"
if [[ "$build_dir" == build/native ]]; then
    cmake --preset native >/dev/null
else
    cmake --preset native -B "$build_dir" >/dev/null
fi
cmake --build "$build_dir" --target bvh_vs_embree
bench=$build_dir/bench/bvh_vs_embree

# 3. The ≥ 1M-triangle mesh (1 046 528 triangles, ~40 MB), written once.
if [[ ! -s "$big" ]]; then
    echo "writing $big" >&2
    python3 scripts/make_big_mesh.py 1024 >"$big.tmp" && mv "$big.tmp" "$big"
fi

# 4. The benchmark (it waits for an idle machine and repeats disturbed runs); the output also
#    goes to $build_dir/bvh_vs_embree.txt.
{
    echo "# $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) CPUs: $(lscpu | sed -n 's/^Model name: *//p')"
    echo "# command: $command"
    "$bench" "${args[@]}" scenes/bunny.obj "$big"
} | tee "$build_dir/bvh_vs_embree.txt"
