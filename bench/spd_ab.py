#!/usr/bin/env python3
"""Two luz binaries side by side on SPD scenes: whole-process wall time of `luz render NAME.nff`,
runs alternating (A, B, then B, A, ...) so that the machine's drift hits both alike; prints each
scene's median times and the median of the pairs' A/B ratios (> 1: B is faster). With
--size 8 it times the start-up (reading the scene, building the BVH), in milliseconds.

usage: bench/spd_ab.py [--size 2048] [--runs 7] [--threads 2] [--spd scenes/spd] A_LUZ B_LUZ NAME...
"""
import argparse
import os
import statistics
import subprocess
import tempfile
import time


def wall(luz, scene, size, threads, out):
    start = time.monotonic()
    subprocess.run([luz, "render", scene, "--width", size, "--height", size, "--threads", threads,
                    "-q", "-o", out], check=True)
    return time.monotonic() - start


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--size", default="2048")
    p.add_argument("--runs", type=int, default=7)
    p.add_argument("--threads", default="2")
    p.add_argument("--spd", default=os.path.join(here, "..", "scenes", "spd"))
    p.add_argument("a")
    p.add_argument("b")
    p.add_argument("names", nargs="+", help="SPD scenes: balls gears mount rings teapot tetra tree")
    args = p.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "out.png")
        for name in args.names:
            scene = os.path.join(args.spd, name + ".nff")
            ta, tb, ratios = [], [], []
            for r in range(args.runs):
                if r % 2 == 0:
                    a = wall(args.a, scene, args.size, args.threads, out)
                    b = wall(args.b, scene, args.size, args.threads, out)
                else:
                    b = wall(args.b, scene, args.size, args.threads, out)
                    a = wall(args.a, scene, args.size, args.threads, out)
                ta.append(a)
                tb.append(b)
                ratios.append(a / b)
            # milliseconds to a tenth for small sizes (start-up: --size 8), else seconds
            ma, mb = statistics.median(ta), statistics.median(tb)
            unit, f = ("ms", 1e3) if max(ma, mb) < 0.1 else ("s", 1.0)
            print(f"{name}: A {ma * f:.{1 if unit == 'ms' else 3}f} {unit}, "
                  f"B {mb * f:.{1 if unit == 'ms' else 3}f} {unit}, "
                  f"A/B {statistics.median(ratios):.3f} (median of {args.runs} pairs)", flush=True)


if __name__ == "__main__":
    main()
