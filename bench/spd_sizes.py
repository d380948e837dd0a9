#!/usr/bin/env python3
# How luz's and POV-Ray 3.7's times grow with the SPD size factor (issue 39): each scene made by
# bench/spd_gen.py at each size, rendered by both (whole process, alternating runs, medians).
# usage: spd_sizes.py [--luz PATH] [--size N] [--threads N] [--runs N] [SCENE:SIZES …]
#   default scenes: balls:3,4,5 rings:5,6,7,8,9,10 tree:11,12,13,14; POV-Ray as bench/spd.sh runs it
import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))


def timed(argv, cwd):
    start = time.monotonic()
    p = subprocess.run(argv, cwd=cwd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    if p.returncode != 0:
        sys.exit(f"failed ({p.returncode}): {' '.join(argv)}\n{p.stderr.decode()[-500:]}")
    return time.monotonic() - start


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--luz", default=os.path.join(HERE, "..", "build", "release", "luz"))
    ap.add_argument("--size", type=int, default=512, help="image width and height")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("plan", nargs="*", default=["balls:3,4,5", "rings:5,6,7,8,9,10",
                                                "tree:11,12,13,14"])
    a = ap.parse_args()
    a.luz = os.path.abspath(a.luz)  # the renders run in a scratch folder
    work = tempfile.mkdtemp(prefix="luz_spd_sizes.")
    n, t = str(a.size), str(a.threads)
    print(f"# {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}; load "
          f"{os.getloadavg()[0]:.2f}; {a.size}², {a.threads} threads, median of {a.runs} "
          "alternating runs, whole process")
    print("| scene | size factor | objects | luz | POV-Ray | ratio |\n|---|---|---|---|---|---|")
    for item in a.plan:
        scene, sizes = item.split(":")
        for sf in sizes.split(","):
            out = os.path.join(work, f"{scene}{sf}")
            subprocess.run([sys.executable, os.path.join(HERE, "spd_gen.py"), scene, sf,
                            "--out", out], check=True)
            nff, pov = os.path.join(out, scene + ".nff"), os.path.join(out, scene + ".pov")
            objects = sum(1 for line in open(nff) if line[:2] in ("s ", "c ", "p "))
            t_luz, t_pov = [], []
            for _ in range(a.runs):
                t_luz.append(timed([a.luz, "render", nff, "--width", n, "--height", n,
                                    "--threads", t, "-q", "-o", out + "/luz.png"], out))
                t_pov.append(timed(["povray", "+I" + pov, f"+W{n}", f"+H{n}", f"+WT{t}", "-D",
                                    "-GA", "+O" + out + "/pov.png"], out))
            lz, pv = statistics.median(t_luz), statistics.median(t_pov)
            print(f"| {scene} | {sf} | {objects} | {lz:.3f} s | {pv:.3f} s | {pv / lz:.1f}× |",
                  flush=True)


if __name__ == "__main__":
    main()
