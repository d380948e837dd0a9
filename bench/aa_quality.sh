#!/usr/bin/env bash
# Antialiasing speed and quality (docs/BENCHMARKS.md, "Antialiasing"): demo:whitted at 800×600
# with luz's none, grid 4, grid 16 and adaptive (threshold 0.05, 0.1, 0.3; max_level 3), timed
# and compared with a 64-sample grid render (RMSE), and POV-Ray 3.7's +A0.3 +AM2 +R3 on the
# equivalent scene bench/whitted.pov in the same run. Installs what it needs (POV-Ray, gnuplot),
# builds luz (Release, -march=native), prints the table and writes the plot.
#
# usage: bench/aa_quality.sh [--build DIR] [--runs N] [--threads N] [--plot PNG]
#   --build DIR   build directory (default build/native, the `native` preset)
#   --runs N      timed runs per setting, median reported (default 3)
#   --threads N   threads for luz (--threads) and POV-Ray (+WT) (default: all cores)
#   --plot PNG    where the error-against-time plot goes (default docs/aa_quality.png)
set -euo pipefail

repo=$(cd "$(dirname "$0")/.." && pwd)
command="bench/aa_quality.sh $*"
build=build/native
runs=3
threads=$(nproc)
plot=docs/aa_quality.png
while (($#)); do
    case "$1" in
        --build) build=$2; shift 2 ;;
        --runs) runs=$2; shift 2 ;;
        --threads) threads=$2; shift 2 ;;
        --plot) plot=$2; shift 2 ;;
        *) echo "unknown option: $1" >&2; exit 2 ;;
    esac
done

# 1. Debian packages: the build dependencies, POV-Ray 3.7, gnuplot (PNG plot), python3.
packages=(cmake ninja-build g++ pkg-config nlohmann-json3-dev libcli11-dev libpng-dev
          libopenexr-dev libtbb-dev libgtest-dev libgmock-dev libtinyobjloader-dev povray
          gnuplot-nox python3)
"$repo/bench/install_packages.sh" "${packages[@]}"

# 2. Build luz: the `native` preset, or the same settings in another folder.
cd "$repo"
if [[ "$build" == build/native ]]; then
    cmake --preset native >/dev/null
else
    cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DLUZ_NATIVE=ON >/dev/null
fi
cmake --build "$build" --target luz >/dev/null

# 3. POV-Ray's scene: written alongside bench/whitted_vs_povray.sh, the same as demo:whitted.
pov=bench/whitted.pov
[[ -f "$pov" ]] || { echo "missing $pov" >&2; exit 1; }

# 4. Run, measure, tabulate, plot; the images stay in a temporary folder.
out=$(mktemp -d /tmp/luz_aa_quality.XXXXXX)
trap 'rm -rf "$out"' EXIT
echo "# $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) CPUs: $(lscpu | sed -n 's/^Model name: *//p')"
echo "# command: $command; $(povray --version 2>&1 | grep -m1 '^POV-Ray')"
python3 bench/aa_quality.py --luz "$build/luz" --pov "$pov" --out "$out" --plot "$plot" \
    --runs "$runs" --threads "$threads"
