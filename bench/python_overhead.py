#!/usr/bin/python3
"""The Python module's cost against the command line (docs/BENCHMARKS.md, "Python module").

  1. a tiny render (16×12 demo:whitted, raytrace): luz.render() in this process against a
     whole `luz render` process (start, load, render, PNG written) and against the render time
     that process reports in --stats;
  2. a 1024×1024 demo:whitted render (raytrace): luz.render() against `luz render` writing a
     .pfm, and against the time the CLI itself reports in --stats (its render alone).

Runs are interleaved (Python, CLI, Python, CLI …) and medians reported, so that a load that
comes and goes on the machine hits both alike.

    PYTHONPATH=build/release/python /usr/bin/python3 bench/python_overhead.py \\
        [--luz build/release/luz] [--runs 7] [--tiny-runs 200] [--threads 0]
"""

import argparse
import json
import os
import pathlib
import statistics
import subprocess
import sys
import tempfile
import time

import luz


def median_ms(xs):
    return statistics.median(xs) * 1000


def main():
    here = pathlib.Path(__file__).resolve().parent
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--luz", default=str(here.parent / "build" / "release" / "luz"))
    ap.add_argument("--runs", type=int, default=7, help="1024² renders each way")
    ap.add_argument("--tiny-runs", type=int, default=200, help="tiny renders each way")
    ap.add_argument("--threads", type=int, default=0)
    a = ap.parse_args()
    tmp = pathlib.Path(tempfile.mkdtemp())

    # 1. Tiny: the per-call cost.
    tiny = dict(width=16, height=12)
    scene = luz.load("demo:whitted")
    py_tiny, py_tiny_load, cli_tiny, cli_tiny_stats = [], [], [], []
    cli = [a.luz, "render", "demo:whitted", "--width", "16", "--height", "12", "-q",
           "--threads", str(a.threads), "-o", str(tmp / "t.png"), "--stats", str(tmp / "t.json")]
    for _ in range(3):  # warm up both
        luz.render(scene, threads=a.threads, **tiny)
        subprocess.run(cli, check=True)
    for _ in range(a.tiny_runs):
        t = time.perf_counter()
        luz.render(scene, threads=a.threads, **tiny)
        py_tiny.append(time.perf_counter() - t)
        t = time.perf_counter()
        luz.render("demo:whitted", threads=a.threads, **tiny)  # load + build + render
        py_tiny_load.append(time.perf_counter() - t)
        t = time.perf_counter()
        subprocess.run(cli, check=True)
        cli_tiny.append(time.perf_counter() - t)
        cli_tiny_stats.append(json.loads((tmp / "t.json").read_text())["seconds"])

    # 2. 1024²: the same work, the same time.
    big = dict(width=1024, height=1024)
    whitted = luz.load("demo:whitted")
    py_big, cli_big, cli_big_stats = [], [], []
    cli = [a.luz, "render", "demo:whitted", "--width", "1024", "--height", "1024", "-q",
           "--threads", str(a.threads), "-o", str(tmp / "b.pfm"), "--stats",
           str(tmp / "s.json")]
    luz.render(whitted, threads=a.threads, **big)  # the BVH, the thread pool
    for _ in range(a.runs):
        t = time.perf_counter()
        luz.render(whitted, threads=a.threads, **big)
        py_big.append(time.perf_counter() - t)
        t = time.perf_counter()
        subprocess.run(cli, check=True)
        cli_big.append(time.perf_counter() - t)
        cli_big_stats.append(json.loads((tmp / "s.json").read_text())["seconds"])

    print(f"tiny render (16×12 demo:whitted, {a.tiny_runs} runs each, medians):")
    print(f"  luz.render(scene)            {median_ms(py_tiny):8.3f} ms")
    print(f"  luz.render('demo:whitted')   {median_ms(py_tiny_load):8.3f} ms  (load + build too)")
    print(f"  luz render process (wall)    {median_ms(cli_tiny):8.3f} ms")
    print(f"  luz render --stats seconds   {median_ms(cli_tiny_stats):8.3f} ms")
    print(f"1024×1024 demo:whitted raytrace ({a.runs} runs each, medians):")
    print(f"  luz.render(scene)            {median_ms(py_big):8.1f} ms")
    print(f"  luz render process (wall)    {median_ms(cli_big):8.1f} ms")
    print(f"  luz render --stats seconds   {median_ms(cli_big_stats):8.1f} ms")
    print(f"  Python / CLI --stats         {statistics.median(py_big) / statistics.median(cli_big_stats):8.3f}")
    for f in tmp.iterdir():
        f.unlink()
    tmp.rmdir()


if __name__ == "__main__":
    sys.exit(main())
