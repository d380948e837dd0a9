#!/usr/bin/env python3
"""The figures program behind `luz figures`: renders the lecture's figures with the given luz
binary and scenes, draws the plots with matplotlib, and writes OUT/index.html. The C++ command
gives OUT as a fresh temporary folder and renames it into place when this exits 0."""

import argparse
import os
import shutil
import sys
import time

sys.dont_write_bytecode = True  # an installed share/luz/figures/ may be read-only
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))


def main():
    """Parses --luz, --scenes and --out, makes every figure group in turn, writes the page."""
    p = argparse.ArgumentParser(description=__doc__)
    p.add_argument("--luz", required=True, help="the luz binary to run")
    p.add_argument("--scenes", required=True, help="folder holding figures/*.json and bunny.obj")
    p.add_argument("--out", required=True, help="folder to write into (exists, empty)")
    p.add_argument("--only", default="", help="comma-separated figure groups (development)")
    a = p.parse_args()
    try:
        import numpy  # noqa: F401
        import matplotlib  # noqa: F401
    except ImportError as e:
        print(f"luz figures: {e.name or 'matplotlib'} is missing: install Debian's "
              "python3-matplotlib (apt-get install python3-matplotlib python3-numpy)",
              file=sys.stderr)
        return 1
    from luzfig import GROUPS, common, page

    t0 = time.perf_counter()
    ctx = common.Context(a.luz, a.scenes, a.out)
    only = set(filter(None, a.only.split(",")))
    for name, module in GROUPS:
        if only and name not in only:
            continue
        t = time.perf_counter()
        try:
            module.make(ctx)
        except Exception as e:  # one line naming the group; the C++ side cleans up
            print(f"luz figures: {name}: {type(e).__name__}: {e}", file=sys.stderr)
            return 1
        print(f"luz figures: {name} ({time.perf_counter() - t:.1f} s)", file=sys.stderr)
    common.copy_scene_files(ctx)
    ctx.web = common.write_web_page(ctx)
    shutil.rmtree(os.path.join(a.out, "work"))
    page.write(ctx, time.perf_counter() - t0)
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except KeyboardInterrupt:  # Ctrl-C when run by hand: no traceback (`luz figures` sends TERM)
        sys.exit(130)
