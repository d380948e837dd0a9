#!/usr/bin/env bash
# Issue 37's "no speed lost" table: every figure of docs/BENCHMARKS.md's head table measured with
# an old tree's build and a new tree's build side by side, runs alternating (old, new, new, old,
# old, new … so that drift hits both alike), 2 threads, medians, one markdown table.
#
# usage: bench/old_vs_new.sh [--runs N] [--quick] [--only REGEX] [--spd DIR] [--big-mesh PATH]
#                            OLD_BUILD NEW_BUILD
#   OLD_BUILD, NEW_BUILD  build folders (Release, no PGO/LTO, LUZ_BUILD_BENCH=ON), each with
#                 luz (+ luz_viewer.so), bench/bvh_vs_embree and bench/zbuffer_vs_llvmpipe
#                 (and NEW_BUILD bench/nff_to_json while OLD_BUILD's luz reads no NFF)
#   --runs N      runs of each tree per workload (default 5)
#   --quick       one run each at small sizes: a smoke test of the script, not a measurement
#   --only REGEX  only the workloads whose name matches (Python re.search), e.g. 'whitted|spd'
#   --spd DIR     the SPD folder (default ../shared/spd beside the repository, or /work/shared/spd)
#   --big-mesh PATH  the 1M-triangle OBJ of the Embree rows (default /tmp/luz_bigmesh.obj,
#                 written by scripts/make_big_mesh.py 1024 if missing)
#   --list        print the workload names and exit
# Workloads (names for --only): whitted-800x600, whitted-3200x2400 (`luz render demo:whitted`,
# whitted_vs_povray.sh's command, whole process: wall and CPU = user + sys); embree-bunny,
# embree-1M (luz's scene query in each tree's bvh_vs_embree --scene --threads 2: primary
# perspective and orthographic, incoherent, one ray at a time and packets of 8, Mrays/s, and
# the Bvh8 build on 2 threads, median of 7 builds: the 1M one varies ±10 % from one to the
# next); zbuffer-5k, -100k, -1M (luz's 2-thread ms per frame from each tree's
# zbuffer_vs_llvmpipe --luz-only); viewer (`xvfb-run -a luz view demo:whitted
# --benchmark`, the full 640x480 pass); spd-NAME (the seven SPD scenes at 512², whole process,
# the same file for both trees: NAME.nff when both read NFF, else a JSON + OBJ conversion by the
# new tree's bench/nff_to_json (same rays; not for tree's truncated cones), else
# SPD/json/NAME/scene.json, else skipped). A workload whose trees trace different ray counts
# (luz --stats) is flagged under the table.
set -euo pipefail

repo=$(cd "$(dirname "$0")/.." && pwd)
command="bench/old_vs_new.sh $*"
runs=5
quick=0
only=""
spd=$repo/../shared/spd
[[ -d "$spd" ]] || spd=/work/shared/spd
big=/tmp/luz_bigmesh.obj
list=0
dirs=()
while (($#)); do
    case "$1" in
        --runs) runs=$2; shift ;;
        --quick) quick=1 ;;
        --only) only=$2; shift ;;
        --spd) spd=$2; shift ;;
        --big-mesh) big=$2; shift ;;
        --list) list=1 ;;
        -h | --help) sed -n '2,28p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
        -*) echo "old_vs_new.sh: unknown option $1 (see --help)" >&2; exit 2 ;;
        *) dirs+=("$1") ;;
    esac
    shift
done
if ((!list)) && ((${#dirs[@]} != 2)); then
    echo "old_vs_new.sh: give two build folders, OLD_BUILD NEW_BUILD (see --help)" >&2
    exit 2
fi
if ! [[ "$runs" =~ ^[1-9][0-9]*$ ]]; then
    echo "old_vs_new.sh: --runs needs a whole number >= 1, got '$runs'" >&2
    exit 2
fi
command -v python3 >/dev/null || { echo "old_vs_new.sh: python3 is missing" >&2; exit 2; }

work=$(mktemp -d /tmp/luz_old_vs_new.XXXXXX)
trap 'rm -rf "$work"' EXIT
export REPO="$repo" RUNS=$runs QUICK=$quick ONLY="$only" SPD="$spd" BIG_MESH="$big" \
    WORK="$work" COMMAND="$command" LIST=$list \
    OLD_BUILD="${dirs[0]:-}" NEW_BUILD="${dirs[1]:-}"
exec python3 - <<'EOF'
import json, os, re, shutil, statistics, subprocess, sys, time

repo, work = os.environ["REPO"], os.environ["WORK"]
runs, quick = int(os.environ["RUNS"]), os.environ["QUICK"] == "1"
if quick:
    runs = 1
only = re.compile(os.environ["ONLY"]) if os.environ["ONLY"] else None
spd, big_mesh = os.environ["SPD"], os.environ["BIG_MESH"]
THREADS = 2
SPD_SCENES = ["balls", "gears", "mount", "rings", "teapot", "tetra", "tree"]


def fail(message):
    sys.exit(f"old_vs_new.sh: {message}")


# --- the workloads ---------------------------------------------------------------------------
# Each workload is run once per tree per round; one run gives one or more figures (a dict
# name -> value). kind "time": lower is better; "rate": higher is better.

class Workload:
    def __init__(self, name, needs, run, figures):
        self.name, self.needs, self.run, self.figures = name, needs, run, figures
        # figures: [(key, label, unit, kind)]


def whitted(w, h):
    def run(tree):
        out = os.path.join(work, f"{tree.tag}.png")
        stats = os.path.join(work, f"{tree.tag}.json")
        wall, cpu = timed([tree.luz, "render", "demo:whitted", "--width", str(w), "--height",
                           str(h), "--threads", str(THREADS), "-o", out, "--quiet",
                           "--stats", stats])
        rays = json.load(open(stats)).get("rays", {})
        return {"wall": wall, "cpu": cpu}, sum(v for v in rays.values() if isinstance(v, int))
    return run


def spd_scene(name, size):
    def run(tree):
        scene = tree.spd_scene[name]
        wall, cpu = timed([tree.luz, "render", scene, "--width", str(size), "--height", str(size),
                           "--threads", str(THREADS), "-q", "-o",
                           os.path.join(work, f"{tree.tag}_{name}.png"), "--stats",
                           os.path.join(work, f"{tree.tag}_{name}.json")])
        rays = json.load(open(os.path.join(work, f"{tree.tag}_{name}.json"))).get("rays", {})
        return {"wall": wall, "cpu": cpu}, sum(v for v in rays.values() if isinstance(v, int))
    return run


def embree(mesh_args, mesh_name):
    def run(tree):
        argv = [tree.bvh_bench, "--scene", "--threads", str(THREADS), "--idle-wait", "0"]
        argv += (["--size", "128", "--reps", "1", "--build-reps", "1"] if quick
                 else ["--build-reps", "7"])
        text = output(argv + mesh_args(tree))
        fig = {}
        section = None
        for line in text.splitlines():
            if line.startswith("Packets,"):
                section = "packets"
            elif line.startswith("Build,"):
                section = "build"
            elif line.startswith("Targets"):
                section = None
            f = line.split()
            if section == "packets" and len(f) >= 6 and f[0] == mesh_name and f[3] == "2" \
                    and f[1] in ("perspective", "orthographic", "incoherent"):
                fig[f"{f[1]}-1"], fig[f"{f[1]}-8"] = float(f[4]), float(f[5])
            elif section == "build" and len(f) >= 4 and f[0] == mesh_name:
                fig["build"] = float(f[3])  # Bvh8_2t (one thread count: Bvh_2t Bvh8_2t …)
        missing = [k for k in ("perspective-1", "perspective-8", "orthographic-1",
                               "orthographic-8", "incoherent-1", "incoherent-8", "build")
                   if k not in fig]
        if missing:
            fail(f"could not read {', '.join(missing)} for {mesh_name} from "
                 f"{' '.join(argv + mesh_args(tree))}:\n{text[-2000:]}")
        return fig, None
    return run


EMBREE_FIGURES = [(f"{rays}-{n}", f"{label}, {how}", "Mrays/s", "rate")
                  for rays, label in (("perspective", "primary perspective"),
                                      ("orthographic", "primary orthographic"),
                                      ("incoherent", "incoherent"))
                  for n, how in (("1", "one ray at a time"), ("8", "packets of 8"))] + \
                 [("build", "Bvh8 build, 2 threads", "ms", "time")]


def zbuffer(size):
    def run(tree):
        argv = [tree.zbuffer_bench, "--luz-only", "--no-breakdown", "--idle-wait", "0",
                "--sizes", size]
        argv += ["--frames", "2", "--seconds", "0"] if quick else ["--frames", "30",
                                                                   "--seconds", "3"]
        text = output(argv)
        fig, table = {}, None
        for line in text.splitlines():
            f = line.split()
            if line.startswith("size  triangles  luz_1t_ms"):
                table = "ms"
            elif line.startswith("size  luz_1t_cpu"):
                table = "cpu"
            elif line.startswith("size "):
                table = None
            elif table == "ms" and f and f[0] == size and len(f) >= 4:
                fig["ms"] = float(f[3])  # luz_2t_ms
            elif table == "cpu" and f and f[0] == size and len(f) >= 3:
                fig["cpu"] = float(f[2])  # luz_2t_cpu
        if "ms" not in fig or "cpu" not in fig:
            fail(f"could not read luz_2t_ms from {' '.join(argv)}:\n{text[-2000:]}")
        return fig, None
    return run


def viewer(w, h):
    def run(tree):
        argv = ["xvfb-run", "-a", tree.luz, "view", "demo:whitted", "--benchmark", "--width",
                str(w), "--height", str(h), "--threads", str(THREADS)]
        text = output(argv)
        for line in text.splitlines():
            m = re.match(r"pass 1/1\s+(\d+)x(\d+)\s+([0-9.]+) ms\s+([0-9.]+) fps", line)
            if m:  # the full pass without antialiasing
                return {"ms": float(m.group(3))}, None
        fail(f"no full-resolution pass line in the output of {' '.join(argv)}:\n{text[-2000:]}")
    return run


ws, wl = ((320, 240), (640, 480)) if quick else ((800, 600), (3200, 2400))
spd_size = 128 if quick else 512
workloads = [
    Workload(f"whitted-800x600", ["luz"], whitted(*ws),
             [("wall", f"demo:whitted {ws[0]}×{ws[1]}, whole process", "s", "time")]),
    Workload(f"whitted-3200x2400", ["luz"], whitted(*wl),
             [("wall", f"demo:whitted {wl[0]}×{wl[1]}, whole process", "s", "time")]),
    Workload("embree-bunny", ["bvh"],
             embree(lambda t: [os.path.join(repo, "scenes/bunny.obj")], "bunny.obj"),
             [(k, "bunny: " + l, u, kd) for k, l, u, kd in EMBREE_FIGURES]),
    Workload("embree-1M", ["bvh", "bigmesh"],
             embree(lambda t: ["--sphere", "64"] if quick else [big_mesh],
                    "sphere_64" if quick else os.path.basename(big_mesh)),
             [(k, ("sphere_64 (quick)" if quick else "1M") + ": " + l, u, kd)
              for k, l, u, kd in EMBREE_FIGURES]),
] + [
    Workload(f"zbuffer-{s}", ["zbuffer"], zbuffer(s),
             [("ms", f"zbuffer, torus {s} at 1024², 2 threads", "ms/frame", "time")])
    for s in ("5k", "100k", "1M")
] + [
    Workload("viewer", ["viewer"], viewer(*((160, 120) if quick else (640, 480))),
             [("ms", "viewer, demo:whitted full pass "
               + ("160×120" if quick else "640×480"), "ms", "time")]),
] + [
    Workload(f"spd-{n}", ["luz", "spd"], spd_scene(n, spd_size),
             [("wall", f"SPD {n} {spd_size}², whole process", "s", "time")])
    for n in SPD_SCENES
]
if os.environ["LIST"] == "1":
    print("\n".join(w.name for w in workloads))
    sys.exit(0)
workloads = [w for w in workloads if only is None or only.search(w.name)]
if not workloads:
    fail(f"--only {os.environ['ONLY']!r} matches no workload (see --list)")
needs = {n for w in workloads for n in w.needs}


# --- timing ----------------------------------------------------------------------------------

def timed(argv):
    """Wall seconds and CPU seconds (user + sys, from wait4: what /usr/bin/time -f '%U %S'
    reports, to the microsecond) of one whole process."""
    with open(os.path.join(work, "stderr"), "w") as err:
        t0 = time.perf_counter()
        p = subprocess.Popen(argv, stdout=subprocess.DEVNULL, stderr=err)
        _, status, ru = os.wait4(p.pid, 0)
        wall = time.perf_counter() - t0
    if os.waitstatus_to_exitcode(status) != 0:
        text = open(os.path.join(work, "stderr"), errors="replace").read()
        fail(f"failed ({os.waitstatus_to_exitcode(status)}): {' '.join(argv)}\n{text[-2000:]}")
    return wall, ru.ru_utime + ru.ru_stime


def output(argv):
    p = subprocess.run(argv, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                       errors="replace")
    if p.returncode != 0:
        fail(f"failed ({p.returncode}): {' '.join(argv)}\n{p.stdout[-2000:]}")
    return p.stdout


# --- the two trees ---------------------------------------------------------------------------

class Tree:
    def __init__(self, tag, build):
        if not build or not os.path.isdir(build):
            fail(f"{tag} build folder {build!r} does not exist")
        self.tag, self.build = tag, os.path.realpath(build)
        self.luz = os.path.join(self.build, "luz")
        self.bvh_bench = os.path.join(self.build, "bench", "bvh_vs_embree")
        self.zbuffer_bench = os.path.join(self.build, "bench", "zbuffer_vs_llvmpipe")
        wanted = {"luz": [self.luz], "spd": [self.luz], "bvh": [self.bvh_bench],
                  "zbuffer": [self.zbuffer_bench],
                  "viewer": [self.luz, os.path.join(self.build, "luz_viewer.so")]}
        missing = []
        for need in ("luz", "spd", "viewer", "bvh", "zbuffer"):
            for path in wanted[need] if need in needs else []:
                ok = os.path.isfile(path) and os.access(
                    path, os.R_OK if path.endswith(".so") else os.X_OK)
                if not ok and path not in missing:
                    missing.append(path)
        if missing:
            fail(f"{tag} tree: missing {', '.join(missing)}\n  build them: ninja -C {self.build} "
                 f"luz bvh_vs_embree zbuffer_vs_llvmpipe (nff_to_json too in the new tree), in "
                 f"a build configured with -DLUZ_BUILD_BENCH=ON; the viewer module needs "
                 f"LUZ_BUILD_VIEWER (SDL2, imgui), zbuffer_vs_llvmpipe libosmesa6-dev, "
                 f"bvh_vs_embree libembree-dev")
        source = self.build
        cache = os.path.join(self.build, "CMakeCache.txt")
        if os.path.exists(cache):
            for line in open(cache, errors="replace"):
                if line.startswith("CMAKE_HOME_DIRECTORY:"):
                    source = line.split("=", 1)[1].strip()
        git = subprocess.run(["git", "-C", source, "log", "-1", "--format=%h %cs %s"],
                             capture_output=True, text=True)
        self.commit = git.stdout.strip() or "(not a git tree)"
        self.short = self.commit.split()[0] if git.returncode == 0 and self.commit else tag
        dirty = subprocess.run(["git", "-C", source, "status", "--porcelain", "-uno"],
                               capture_output=True, text=True).stdout.strip()
        if dirty:
            self.commit += " (with uncommitted changes)"
        self.source = source
        self.spd_scene = {}

    def reads_nff(self):
        probe = subprocess.run([self.luz, "render", os.path.join(spd, "balls.nff"), "--width",
                                "8", "--height", "8", "-q", "-o",
                                os.path.join(work, "probe.png")], capture_output=True)
        return probe.returncode == 0


old = Tree("old", os.environ["OLD_BUILD"])
new = Tree("new", os.environ["NEW_BUILD"])
if "viewer" in needs and shutil.which("xvfb-run") is None:
    fail("xvfb-run is missing (apt-get install xvfb)")
if "bigmesh" in needs and not quick and not os.path.exists(big_mesh):
    print(f"writing {big_mesh} (scripts/make_big_mesh.py 1024)", file=sys.stderr)
    with open(big_mesh + ".tmp", "w") as f:
        subprocess.run([sys.executable, os.path.join(repo, "scripts/make_big_mesh.py"), "1024"],
                       stdout=f, check=True)
    os.replace(big_mesh + ".tmp", big_mesh)

# The SPD: the same file for both trees: NAME.nff when both read NFF; else a JSON conversion
# made here by the new tree's bench/nff_to_json (its NFF reader; lights as Il/(d+K), K = 1000,
# for the old format, which has no `attenuation: none`: the same rays); else SPD/json/NAME
# (balls and rings, converted before luz read NFF); else skipped (tree: truncated cones).
skipped, spd_how = {}, {}
if "spd" in needs:
    if not os.path.isdir(spd):
        fail(f"no SPD folder {spd} (--spd DIR)")
    both_nff = old.reads_nff() and new.reads_nff()
    converter = os.path.join(new.build, "bench", "nff_to_json")
    for n in SPD_SCENES:
        if not any(w.name == f"spd-{n}" for w in workloads):
            continue
        nff, js = os.path.join(spd, n + ".nff"), os.path.join(spd, "json", n, "scene.json")
        why = f"the old tree reads no NFF and there is no {os.path.relpath(js, spd)}"
        if both_nff and os.path.exists(nff):
            old.spd_scene[n] = new.spd_scene[n] = nff
            spd_how[n] = "NFF"
            continue
        if os.access(converter, os.X_OK) and os.path.exists(nff):
            out = os.path.join(work, "spd", n)
            p = subprocess.run([converter, nff, out], capture_output=True, text=True)
            if p.returncode == 0:
                old.spd_scene[n] = new.spd_scene[n] = os.path.join(out, "scene.json")
                spd_how[n] = "JSON by nff_to_json"
                continue
            why = p.stderr.strip().splitlines()[-1] if p.stderr.strip() else f"nff_to_json " \
                f"failed ({p.returncode})"
            if p.returncode != 3:
                fail(f"{converter} {nff} {out}: {why}")
        if os.path.exists(js):
            old.spd_scene[n] = new.spd_scene[n] = js
            spd_how[n] = "JSON of SPD/json"
        else:
            skipped[f"spd-{n}"] = why
    workloads = [w for w in workloads if w.name not in skipped]
    for w in workloads:
        if w.name.startswith("spd-"):
            n = w.name[4:]
            w.figures = [(k, f"{l} ({spd_how[n]})", u, kd) for k, l, u, kd in w.figures]


# --- the runs --------------------------------------------------------------------------------

def machine():
    cpu = "?"
    try:
        lscpu = subprocess.run(["lscpu"], capture_output=True, text=True).stdout
        m = re.search(r"^Model name:\s*(.+)$", lscpu, re.M)
        cpu = m.group(1).strip() if m else cpu
    except OSError:
        pass
    return cpu


def load():
    return " ".join(f"{x:.2f}" for x in os.getloadavg())


start = time.time()
load_start = load()
results = {}  # workload name -> {"old": [figs], "new": [figs], "work": {tag: set}}
for w in workloads:
    r = results[w.name] = {"old": [], "new": [], "work": {"old": set(), "new": set()}}
    print(f"{w.name}: {runs} run{'s' if runs > 1 else ''} of each tree, alternating",
          file=sys.stderr, flush=True)
    if "luz" in w.needs and not quick:  # page cache and dynamic loader warm, not timed
        w.run(old); w.run(new)
    for i in range(runs):
        for tree in ((old, new) if i % 2 == 0 else (new, old)):
            t0 = time.perf_counter()
            fig, work_done = w.run(tree)
            r[tree.tag].append(fig)
            if work_done is not None:
                r["work"][tree.tag].add(work_done)
            shown = "  ".join(f"{k} {v:.4g}" for k, v in fig.items())
            print(f"  {tree.tag}  {shown}  ({time.perf_counter() - t0:.1f} s)", file=sys.stderr,
                  flush=True)
end = time.time()

med = statistics.median
print(f"# old against new, {runs} run{'s' if runs > 1 else ''} of each, alternating "
      f"(old, new, new, old, …), medians, {THREADS} threads"
      + ("; --quick: small sizes, one run, NOT a measurement" if quick else ""))
print(f"# machine: {machine()}, {os.cpu_count()} CPUs; load average (1, 5, 15 min) "
      f"{load_start} at the start, {load()} at the end")
print(f"# {time.strftime('%Y-%m-%d %H:%M:%S', time.gmtime(start))} – "
      f"{time.strftime('%H:%M:%S UTC', time.gmtime(end))} ({end - start:.0f} s); "
      f"command: {os.environ['COMMAND']}")
print(f"# old: {old.commit} — {old.build}")
print(f"# new: {new.commit} — {new.build}")
print()
print(f"| workload | unit | old {old.short} | new {new.short} | new/old time | "
      f"old CPU | new CPU | new/old CPU |")
print("|---|---|---|---|---|---|---|---|")
warnings = []
for w in workloads:
    r = results[w.name]
    for key, label, unit, kind in w.figures:
        a, b = med(f[key] for f in r["old"]), med(f[key] for f in r["new"])
        ratio = (b / a if kind == "time" else a / b) if a > 0 and b > 0 else float("nan")
        cpu_cells = "— | — | —"
        if key in ("wall", "ms") and "cpu" in r["old"][0]:
            ca, cb = med(f["cpu"] for f in r["old"]), med(f["cpu"] for f in r["new"])
            cpu_cells = f"{ca:.4g} | {cb:.4g} | {cb / ca:.3f}"
        print(f"| {label} | {unit} | {a:.4g} | {b:.4g} | {ratio:.3f} | {cpu_cells} |")
    if r["work"]["old"] and r["work"]["new"] and r["work"]["old"] != r["work"]["new"]:
        warnings.append(f"{w.name}: the trees traced different ray counts "
                        f"(old {sorted(r['work']['old'])}, new {sorted(r['work']['new'])})")
for name, why in skipped.items():
    print(f"| {name} | — | — | — | — | — | — | — |")
    warnings.append(f"{name} skipped: {why}")
print()
print("(new/old time: the new tree's time over the old tree's, for rates the old rate over the "
      "new;\n below 1 means the new tree is faster. CPU = user + sys of the whole process in "
      "s,\n for the zbuffer rows luz's CPU ms per frame.)")
for text in warnings:
    print(f"NOTE: {text}")
EOF
