#!/usr/bin/env bash
# luz against POV-Ray 3.7 on the seven Standard Procedural Databases scenes (issue 39's table):
# each scene rendered by both, whole-process wall time, 2 threads, runs alternating luz / POV-Ray,
# at 512² and 2048²; medians, and in brackets the range of the runs' own ratios. luz renders
# NAME.nff, or json/NAME/scene.json while it cannot read NFF; POV-Ray renders NAME.pov
# (`povray +I… +W… +H… +WT2 -D -GA`). Ratios to two decimals: 4.98× is not rounded to 5.0×.
#
# usage: bench/spd.sh [--spd DIR] [--sizes "512 2048"] [--runs N] [--threads N] [--scenes "…"]
#   --spd DIR      the SPD folder (default ../shared/spd beside the repository, or /work/shared/spd)
#   --sizes LIST   image sizes, square (default "512 2048")
#   --runs N       runs of each renderer per scene and size, median reported (default 3)
#   --threads N    threads of both renderers (default 2)
#   --scenes LIST  scene names (default "balls gears mount rings teapot tetra tree")
# environment: LUZ=path/to/luz (default build/release/luz, built with the release preset).
set -euo pipefail

repo=$(cd "$(dirname "$0")/.." && pwd)
spd=$repo/../shared/spd
[[ -d "$spd" ]] || spd=/work/shared/spd
sizes="512 2048"
runs=3
threads=2
scenes="balls gears mount rings teapot tetra tree"
while (($#)); do
    case "$1" in
        --spd) spd=$2; shift ;;
        --sizes) sizes=$2; shift ;;
        --runs) runs=$2; shift ;;
        --threads) threads=$2; shift ;;
        --scenes) scenes=$2; shift ;;
        -h | --help) sed -n '2,15p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
        *) echo "unknown option: $1 (see --help)" >&2; exit 2 ;;
    esac
    shift
done
command -v povray >/dev/null || "$repo/bench/install_packages.sh" povray python3

cd "$repo"
if [[ -z "${LUZ:-}" ]]; then
    if [[ ! -x build/release/luz ]]; then
        cmake --preset release >/dev/null
        cmake --build --preset release --target luz
    fi
    LUZ=build/release/luz
fi
LUZ=$(realpath "$LUZ")  # the renders run in a scratch folder

work=$(mktemp -d /tmp/luz_spd.XXXXXX)
trap 'rm -rf "$work"' EXIT
export LUZ SPD="$spd" WORK="$work" SIZES="$sizes" RUNS=$runs THREADS=$threads SCENES="$scenes"
python3 - <<'EOF'
import os, shutil, statistics, subprocess, sys, time

luz, spd, work = os.environ["LUZ"], os.environ["SPD"], os.environ["WORK"]
threads, runs = int(os.environ["THREADS"]), int(os.environ["RUNS"])
sizes = [int(s) for s in os.environ["SIZES"].split()]

def luz_scene(name):
    """NAME.nff if this luz reads it, else the converted JSON, else None."""
    nff = os.path.join(spd, name + ".nff")
    probe = subprocess.run([luz, "render", nff, "--width", "8", "--height", "8", "-q",
                            "-o", os.path.join(work, "probe.png")], capture_output=True)
    if probe.returncode == 0:
        return nff
    js = os.path.join(spd, "json", name, "scene.json")
    return js if os.path.exists(js) else None

def timed(argv, cwd):
    start = time.monotonic()
    p = subprocess.run(argv, cwd=cwd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    wall = time.monotonic() - start
    if p.returncode != 0:
        sys.exit(f"failed ({p.returncode}): {' '.join(argv)}\n{p.stderr.decode()[-500:]}")
    return wall

cpu = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo")
            if l.startswith("model name")), "?")
print(f"# {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, {os.cpu_count()} CPUs: {cpu}; "
      f"load {os.getloadavg()[0]:.2f}; {threads} threads, median of {runs} alternating runs")
head = "| scene | " + " | ".join(f"{s}² luz / POV-Ray | ratio" for s in sizes) + " |"
print(head)
print("|---" * (1 + 2 * len(sizes)) + "|")
for name in os.environ["SCENES"].split():
    scene = luz_scene(name)
    pov = os.path.join(spd, name + ".pov")
    if scene is None or not os.path.exists(pov):
        print(f"| {name} | " + " | ".join("— | —" for _ in sizes) + " |  (no scene luz reads)")
        continue
    cells = []
    for s in sizes:
        t_luz, t_pov = [], []
        for _ in range(runs):
            t_luz.append(timed([luz, "render", scene, "--width", str(s), "--height", str(s),
                                "--threads", str(threads), "-q",
                                "-o", os.path.join(work, f"{name}.png")], work))
            t_pov.append(timed(["povray", "+I" + pov, f"+W{s}", f"+H{s}", f"+WT{threads}",
                                "-D", "-GA", "+O" + os.path.join(work, f"{name}_pov.png")], work))
        a, b = statistics.median(t_luz), statistics.median(t_pov)
        # the ratio of the medians, then the range of the runs' own ratios (each run's POV-Ray
        # time over its luz time): how far one run may land from the median on this machine
        pairs = sorted(p / l for l, p in zip(t_luz, t_pov))
        spread = f" ({pairs[0]:.2f}–{pairs[-1]:.2f})" if runs > 1 else ""
        cells.append(f"{a:.3f} / {b:.3f} s | {b / a:.2f}×{spread}")
    tag = "" if scene.endswith(".nff") else " (JSON)"
    print(f"| {name}{tag} | " + " | ".join(cells) + " |", flush=True)
EOF
