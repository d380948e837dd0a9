#!/usr/bin/env python3
# Antialiasing speed and quality (docs/BENCHMARKS.md, "Antialiasing"): renders demo:whitted with
# luz in every antialiasing setting and POV-Ray's adaptive +A0.3 +AM2 +R3 on bench/whitted.pov,
# times them, measures each luz image's RMSE against a 64-sample grid render, prints a table
# and plots error against time. Run through bench/aa_quality.sh (it installs and builds).
#
# usage: aa_quality.py --luz BIN --pov FILE --out DIR [--plot PNG] [--runs N] [--threads N]
#                      [--width W --height H]
import argparse
import json
import os
import re
import shutil
import statistics
import struct
import subprocess
import sys
import time

# (label, luz options): the settings of the issue; adaptive keeps the default max_level 3.
LUZ_CONFIGS = [
    ("none", ["--aa", "none"]),
    ("grid 4", ["--aa", "grid", "--samples", "4"]),
    ("grid 16", ["--aa", "grid", "--samples", "16"]),
    ("adaptive 0.05", ["--aa", "adaptive", "--threshold", "0.05"]),
    ("adaptive 0.1", ["--aa", "adaptive", "--threshold", "0.1"]),
    ("adaptive 0.3", ["--aa", "adaptive", "--threshold", "0.3"]),
]
REFERENCE = ("grid 64 (reference)", ["--aa", "grid", "--samples", "64"])
POV_CONFIGS = [
    ("POV-Ray no AA", ["-A"]),
    ("POV-Ray +A0.3 +AM2 +R3", ["+A0.3", "+AM2", "+R3"]),
]


def read_pfm(path):
    """Linear RGB floats of a PFM file, row-major from the top, as one flat list."""
    with open(path, "rb") as f:
        data = f.read()
    header, rest = data.split(b"\n", 1)
    assert header.strip() == b"PF", path
    dims, rest = rest.split(b"\n", 1)
    w, h = map(int, dims.split())
    scale, pixels = rest.split(b"\n", 1)
    order = "<" if float(scale) < 0 else ">"
    values = struct.unpack(order + "%df" % (w * h * 3), pixels[: w * h * 12])
    rows = [values[(h - 1 - y) * w * 3 : (h - y) * w * 3] for y in range(h)]  # bottom-up file
    return w, h, [v for row in rows for v in row]


def rmse(a, b):
    """Root mean square difference of values clamped to [0, 1] (what an 8-bit image shows)."""
    total = 0.0
    for x, y in zip(a, b):
        d = min(max(x, 0.0), 1.0) - min(max(y, 0.0), 1.0)
        total += d * d
    return (total / len(a)) ** 0.5


def busy_cores(interval=0.5):
    """CPU cores kept busy by all processes over `interval` seconds (from /proc/stat)."""
    def sample():
        with open("/proc/stat") as f:
            v = list(map(int, f.readline().split()[1:]))
        return sum(v), v[3] + v[4]  # total, idle + iowait
    t0, i0 = sample()
    time.sleep(interval)
    t1, i1 = sample()
    total = max(t1 - t0, 1)
    return (os.cpu_count() or 1) * (1.0 - (i1 - i0) / total)


def wait_idle(limit=0.3, patience=15.0):
    """Waits (at most `patience` s) until other processes leave the CPUs idle: the comparison is
    of wall times on a shared machine."""
    deadline = time.time() + patience
    busy = busy_cores()
    while busy > limit and time.time() < deadline:
        time.sleep(1.0)
        busy = busy_cores()
    return busy


LOAD_BEFORE_RUNS = []  # cores other processes kept busy just before each timed run


def run_timed(cmd):
    """Runs `cmd`; returns its wall time and its standard error."""
    LOAD_BEFORE_RUNS.append(wait_idle())
    start = time.perf_counter()
    proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    seconds = time.perf_counter() - start
    if proc.returncode != 0:
        sys.exit("failed (%d): %s\n%s" % (proc.returncode, " ".join(cmd), proc.stderr.decode()))
    return seconds, proc.stderr.decode(errors="replace")


def pov_trace_seconds(stderr):
    """POV-Ray's own "Trace Time: ... (1.234 seconds)" (the render without start-up)."""
    m = re.search(r"Trace Time:.*\(([0-9.]+) seconds\)", stderr)
    return float(m.group(1)) if m else float("nan")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--luz", required=True)
    ap.add_argument("--pov", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--plot")
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--threads", type=int, default=os.cpu_count())
    ap.add_argument("--width", type=int, default=800)
    ap.add_argument("--height", type=int, default=600)
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    size = ["--width", str(args.width), "--height", str(args.height)]

    def luz_cmd(name, opts):
        base = os.path.join(args.out, name.replace(" ", "_"))
        return base, [args.luz, "render", "demo:whitted", "-q", "-o", base + ".pfm",
                      "--stats", base + ".json", "--threads", str(args.threads)] + size + opts

    def pov_cmd(name, opts):
        base = os.path.join(args.out, name.replace(" ", "_").replace("+", ""))
        return base, ["povray", "-D", "-V", "+I" + args.pov, "+O" + base + ".png",
                      "+W%d" % args.width, "+H%d" % args.height, "+WT%d" % args.threads,
                      "+FN"] + opts

    # The reference, once (not timed).
    ref_base, cmd = luz_cmd(REFERENCE[0].split(" (")[0], REFERENCE[1])
    run_timed(cmd)
    _, _, ref = read_pfm(ref_base + ".pfm")

    # Every configuration `runs` times, in rotating order so that the machine's drift hits all.
    jobs = [("luz",) + c for c in LUZ_CONFIGS] + [("pov",) + c for c in POV_CONFIGS]
    times = {name: [] for _, name, _ in jobs}
    render_times = {name: [] for _, name, _ in jobs}  # luz: --stats seconds; POV-Ray: Trace Time
    for r in range(args.runs):
        for k in range(len(jobs)):
            kind, name, opts = jobs[(k + r) % len(jobs)]
            base, cmd = (luz_cmd if kind == "luz" else pov_cmd)(name, opts)
            wall, stderr = run_timed(cmd)
            times[name].append(wall)
            if kind == "luz":
                with open(base + ".json") as f:
                    render_times[name].append(json.load(f)["seconds"])
            else:
                render_times[name].append(pov_trace_seconds(stderr))

    rows = []
    for kind, name, opts in jobs:
        t = statistics.median(times[name])
        row = {"name": name, "kind": kind, "seconds": t, "all": times[name],
               "render_seconds": statistics.median(render_times[name])}
        if kind == "luz":
            base, _ = luz_cmd(name, opts)
            with open(base + ".json") as f:
                stats = json.load(f)
            row["samples"] = stats["samples"]
            row["refined"] = stats["pixels_refined"]
            row["rmse"] = rmse(read_pfm(base + ".pfm")[2], ref)
        rows.append(row)

    print("%-24s %10s %9s %9s %9s %10s" % ("setting", "samples", "refined", "wall_s", "render_s",
                                          "rmse_255"))
    for r in rows:
        if r["kind"] == "luz":
            print("%-24s %10d %9d %9.3f %9.3f %10.3f" % (r["name"], r["samples"], r["refined"],
                                                      r["seconds"], r["render_seconds"],
                                                      255 * r["rmse"]))
        else:
            print("%-24s %10s %9s %9.3f %9.3f %10s" % (r["name"], "-", "-", r["seconds"],
                                                     r["render_seconds"], "-"))
    luz_ad = next(r for r in rows if r["name"] == "adaptive 0.3")
    pov_ad = next(r for r in rows if r["name"] == POV_CONFIGS[1][0])
    print("ratio POV-Ray +A0.3 +AM2 +R3 / luz adaptive 0.3: wall time %.2f, render time %.2f"
          % (pov_ad["seconds"] / luz_ad["seconds"],
             pov_ad["render_seconds"] / luz_ad["render_seconds"]))
    print("runs per setting: %d, threads: %d; medians; wall_s: the whole process, render_s: "
          "luz's --stats seconds (scene build to image) or POV-Ray's Trace Time; other "
          "processes' load before the runs: median %.2f, max %.2f cores"
          % (args.runs, args.threads, statistics.median(LOAD_BEFORE_RUNS),
             max(LOAD_BEFORE_RUNS)))

    if args.plot and shutil.which("gnuplot"):
        all_times = [r["seconds"] for r in rows if r["kind"] == "luz"] + [pov_ad["seconds"]]
        lo, hi = min(all_times), max(all_times)
        data = os.path.join(args.out, "plot.dat")
        with open(data, "w") as f:
            for r in rows:
                if r["kind"] == "luz":
                    f.write('"%s" %.6f %.6f\n' % (r["name"], r["seconds"], 255 * r["rmse"]))
        script = """
set terminal png size 900,560 font ",11"
set output "%s"
set title "demo:whitted %dx%d, %d threads: error against time"
set xlabel "wall time per render (s, log scale)"
set ylabel "RMSE against a 64-sample grid (8-bit units)"
set logscale x
set xrange [%f:%f]
set grid
set key top right
set arrow from %f, graph 0 to %f, graph 1 nohead dashtype 2 lw 2 lc rgb "#c03030"
set label "POV-Ray +A0.3 +AM2 +R3" at first %f, graph 0.95 right offset -0.5,0 tc rgb "#c03030"
plot "%s" using 2:3 with points pt 7 ps 1.6 lc rgb "#2060c0" title "luz (raytrace)", \\
     "" using 2:3:1 with labels offset 0,1.1 notitle
""" % (args.plot, args.width, args.height, args.threads, lo / 1.5, hi * 1.5, pov_ad["seconds"],
       pov_ad["seconds"], pov_ad["seconds"], data)
        subprocess.run(["gnuplot"], input=script.encode(), check=True)
        print("plot: %s" % args.plot)


if __name__ == "__main__":
    main()
