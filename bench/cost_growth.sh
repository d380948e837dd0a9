#!/usr/bin/env bash
# How cost grows (docs/BENCHMARKS.md): BVH build time, bytes per triangle and rays/s of luz
# and Embree 3 against triangle count (bench/bvh_vs_embree --sphere, 10k … 10M triangles), and
# luz's render time of demo:whitted against resolution and against max depth; writes CSVs into
# the build dir, prints the tables and plots them (bench/plot_cost_growth.py → docs/*.png).
#
# usage: bench/cost_growth.sh [--build-dir DIR] [--jobs N] [--threads LIST] [--spheres LIST]
#                             [--size N] [--reps N] [--runs N] [--quick] [--plot-dir DIR]
#                             [--no-wait] [--no-plot] [-- BVH_VS_EMBREE OPTIONS...]
#   --build-dir DIR  build there with the native preset's settings (default build/native);
#                    the CSVs and the output (cost_growth*.csv, cost_growth.txt) go there too
#   --jobs N         parallel build jobs (default 2)
#   --threads LIST   bvh_vs_embree's thread counts (default 1,2); luz renders with the last
#   --spheres LIST   sphere segments N, N·(N/2−1)·2 triangles (default 100,174,318,548,1000,
#                    1732,3164: ~10k, 30k, 100k, 300k, 1M, 3M, 10M triangles)
#   --size N         bvh_vs_embree's N×N primary rays (default 1024)
#   --reps N         bvh_vs_embree's timed passes (default 5)
#   --runs N         luz renders per resolution and per depth, median (default 5)
#   --quick          smoke test: spheres 64,128, --size 128, --reps 1, --build-reps 1, 3 runs,
#                    3 resolutions and depths 0,1,2,5; plots into DIR/cost_growth_plots
#   --plot-dir DIR   where the PNGs go (default docs/, or as --quick says)
#   --no-wait        do not wait for idle CPUs before measuring (bvh_vs_embree --idle-wait 0)
#   --no-plot        write the CSVs and tables only
#   after --        more options for bvh_vs_embree (see its --help)
set -euo pipefail

repo=$(cd "$(dirname "$0")/.." && pwd)
command="bench/cost_growth.sh $*"
build_dir=build/native
jobs=2
threads=1,2
spheres=100,174,318,548,1000,1732,3164
size=1024
reps=5
runs=5
quick=0
plot_dir=
wait_idle=1
plot=1
resolutions="200x150 283x212 400x300 566x424 800x600 1131x848 1600x1200 2263x1697 3200x2400"
depths="0 1 2 3 4 5 6 7 8 9 10"
extra=()
while (($#)); do
    case "$1" in
        --build-dir) build_dir=$2; shift ;;
        --jobs) jobs=$2; shift ;;
        --threads) threads=$2; shift ;;
        --spheres) spheres=$2; shift ;;
        --size) size=$2; shift ;;
        --reps) reps=$2; shift ;;
        --runs) runs=$2; shift ;;
        --quick) quick=1 ;;
        --plot-dir) plot_dir=$2; shift ;;
        --no-wait) wait_idle=0 ;;
        --no-plot) plot=0 ;;
        --) shift; extra=("$@"); break ;;
        -h | --help) sed -n '2,24p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
        *) echo "unknown option: $1 (see --help)" >&2; exit 2 ;;
    esac
    shift
done
if ((quick)); then
    spheres=64,128
    size=128
    reps=1
    runs=3
    resolutions="200x150 400x300 800x600"
    depths="0 1 2 5"
    extra=(--build-reps 1 "${extra[@]}")
fi
render_threads=${threads##*,}

# 1. Debian packages: the project's build dependencies, Embree 3, python3 with matplotlib.
packages=(cmake ninja-build g++ pkg-config nlohmann-json3-dev libcli11-dev libpng-dev
          libopenexr-dev libtbb-dev libgtest-dev libgmock-dev libtinyobjloader-dev
          libembree-dev python3 python3-numpy python3-matplotlib)
"$repo/bench/install_packages.sh" "${packages[@]}"

# 2. Configure and build the two targets with the `native` preset (Release, -march=native).
cd "$repo"
if [[ "$build_dir" == build/native ]]; then
    cmake --preset native >/dev/null
else
    cmake --preset native -B "$build_dir" >/dev/null
fi
cmake --build "$build_dir" -j "$jobs" --target bvh_vs_embree luz >&2
build_dir=$(cd "$build_dir" && pwd)
bench=$build_dir/bench/bvh_vs_embree
luz=$build_dir/luz
bvh_csv=$build_dir/cost_growth_bvh.csv
resolution_csv=$build_dir/cost_growth_resolution.csv
depth_csv=$build_dir/cost_growth_depth.csv
if [[ -z "$plot_dir" ]]; then
    plot_dir=$repo/docs
    ((quick)) && plot_dir=$build_dir/cost_growth_plots
fi
rm -f "$bvh_csv" "$resolution_csv" "$depth_csv"

{
    echo "# $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) CPUs: $(lscpu | sed -n 's/^Model name: *//p')"
    echo "# command: $command"
    echo "# $(free -g | awk '/^Mem:/ {print $2 " GiB RAM"}'); CSVs: $bvh_csv, $resolution_csv, $depth_csv"

    # 3. Build time, memory and rays/s against triangle count (bvh_vs_embree waits for an idle
    #    machine and repeats disturbed runs unless --no-wait).
    echo
    echo "## BVH against Embree by triangle count: bvh_vs_embree --scene --threads $threads" \
        "--size $size --reps $reps --sphere $spheres ${extra[*]}"
    idle=()
    ((wait_idle)) || idle=(--idle-wait 0)
    "$bench" --scene --threads "$threads" --size "$size" --reps "$reps" "${idle[@]}" \
        --sphere "$spheres" --csv "$bvh_csv" "${extra[@]}"

    # 4. luz render demo:whitted against resolution (at its own max depth, 5), and against
    #    max depth at 800x600: the
    #    median of --runs renders of the --stats `seconds` (the render) and of the whole
    #    process's wall time, each after waiting (up to 60 s) for idle CPUs.
    echo
    echo "## luz render demo:whitted, $render_threads threads, median of $runs runs"
    LUZ=$luz THREADS=$render_threads RUNS=$runs RESOLUTIONS=$resolutions DEPTHS=$depths \
        WAIT_IDLE=$wait_idle RESOLUTION_CSV=$resolution_csv DEPTH_CSV=$depth_csv \
        python3 - <<'EOF'
import atexit, csv, json, os, shutil, statistics, subprocess, sys, tempfile, time

luz, threads, runs = os.environ["LUZ"], int(os.environ["THREADS"]), int(os.environ["RUNS"])
wait_idle = os.environ["WAIT_IDLE"] == "1"
HZ = os.sysconf("SC_CLK_TCK")
IDLE_CORES = 0.15  # "idle" = all other processes together use less than this many cores

def busy_seconds():
    """CPU seconds spent by all processes since boot (every core), from /proc/stat."""
    f = [int(x) for x in open("/proc/stat").readline().split()[1:]]
    return (sum(f[:8]) - f[3] - f[4]) / HZ  # all but idle and iowait

def wait_for_idle(timeout=60.0):
    start = time.monotonic()
    while wait_idle and time.monotonic() - start < timeout:
        b0 = busy_seconds(); time.sleep(0.5)
        if busy_seconds() - b0 < IDLE_CORES * 0.5:
            return

work = tempfile.mkdtemp(prefix="cost_growth.")
atexit.register(shutil.rmtree, work, True)
def render(w, h, depth=None):
    """One render: (wall s, --stats JSON)."""
    argv = [luz, "render", "demo:whitted", "--width", str(w), "--height", str(h),
            "--threads", str(threads), "-o", f"{work}/out.ppm", "--quiet",
            "--stats", f"{work}/stats.json"]
    if depth is not None:
        argv += ["--max-depth", str(depth)]
    wait_for_idle()
    t0 = time.perf_counter()
    subprocess.run(argv, check=True)
    return time.perf_counter() - t0, json.load(open(f"{work}/stats.json"))

FIELDS = ["width", "height", "pixels", "max_depth", "threads", "runs", "render_s", "wall_s",
          "render_s_min", "render_s_max", "primary", "shadow", "reflection", "refraction",
          "rays", "mrays_per_s", "peak_memory_mib"]

def sweep(points, path, title):
    rows = []
    for w, h, depth in points:
        render(w, h, depth)  # warm-up (page cache), not counted
        walls, stats = [], []
        for _ in range(runs):
            wall, s = render(w, h, depth)
            walls.append(wall); stats.append(s)
        secs = [s["seconds"] for s in stats]
        rays = stats[-1]["rays"]
        total = sum(rays[k] for k in ("primary", "shadow", "reflection", "refraction"))
        med = statistics.median(secs)
        rows.append({"width": w, "height": h, "pixels": w * h,
                     "max_depth": "" if depth is None else depth, "threads": threads,
                     "runs": runs, "render_s": f"{med:.5f}",
                     "wall_s": f"{statistics.median(walls):.5f}",
                     "render_s_min": f"{min(secs):.5f}", "render_s_max": f"{max(secs):.5f}",
                     **{k: rays[k] for k in ("primary", "shadow", "reflection", "refraction")},
                     "rays": total, "mrays_per_s": f"{total / med / 1e6:.3f}",
                     "peak_memory_mib": f"{stats[-1]['peak_memory_bytes'] / 2**20:.1f}"})
        print(f"  {w}x{h}" + ("" if depth is None else f" depth {depth}")
              + f": {med:.4f} s", file=sys.stderr, flush=True)
    with open(path, "w", newline="") as f:
        out = csv.DictWriter(f, FIELDS)
        out.writeheader(); out.writerows(rows)
    print(f"\n{title}")
    print(f"{'size':>10} {'depth':>5} {'pixels':>9} {'render_s':>9} {'min':>8} {'max':>8} "
          f"{'wall_s':>8} {'ns/pixel':>9} {'Mrays':>8} {'Mrays/s':>8} {'peak_MiB':>8}")
    for r in rows:
        print(f"{str(r['width']) + 'x' + str(r['height']):>10} {str(r['max_depth']) or '-':>5} "
              f"{r['pixels']:9d} {r['render_s']:>9} {r['render_s_min']:>8} "
              f"{r['render_s_max']:>8} {r['wall_s']:>8} "
              f"{float(r['render_s']) / r['pixels'] * 1e9:9.1f} {r['rays'] / 1e6:8.2f} "
              f"{r['mrays_per_s']:>8} {r['peak_memory_mib']:>8}")

sizes = [tuple(int(v) for v in s.split("x")) for s in os.environ["RESOLUTIONS"].split()]
sweep([(w, h, 5) for w, h in sizes], os.environ["RESOLUTION_CSV"],  # 5: the scene's own
      "render time against resolution (--max-depth 5); render_s = --stats seconds")
sweep([(800, 600, int(d)) for d in os.environ["DEPTHS"].split()], os.environ["DEPTH_CSV"],
      "render time against max depth at 800x600 (--max-depth)")
EOF
} | tee "$build_dir/cost_growth.txt"

# 5. The plots.
if ((plot)); then
    mkdir -p "$plot_dir"
    /usr/bin/python3 "$repo/bench/plot_cost_growth.py" --bvh "$bvh_csv" \
        --resolution "$resolution_csv" --depth "$depth_csv" --out "$plot_dir"
fi
