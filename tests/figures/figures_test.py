#!/usr/bin/python3
"""The full `luz figures` run (CTest: Figures.*). Usage:
  figures_test.py run LUZ DIR       runs `luz figures -o DIR`, checks it took under the time
                                    limit, that every figure's image exists and index.html
                                    references every image, scene file and figure id
  figures_test.py chromium DIR SHOT opens DIR/index.html in headless Chromium: every <img>
                                    loaded (naturalWidth > 0, the page's own status line), no
                                    console errors; keeps a screenshot at SHOT."""

import glob
import html
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
import urllib.parse

LIMIT_SECONDS = 120
FIGURES = ["diffuse_specular", "lambert", "distance", "specular_n", "specular_ks", "terms",
           "reflectance", "coloured_lights", "local_global", "max_depth", "tree_attenuation",
           "snell", "ray_tree", "antialias", "bounding_volumes", "speed", "spd",
           "primitives", "materials"]


def fail(msg):
    print("FAIL: " + msg)
    sys.exit(1)


def run(luz, out):
    if os.path.exists(out):
        shutil.rmtree(out)
    t0 = time.perf_counter()
    r = subprocess.run([luz, "figures", "-o", out], capture_output=True, text=True)
    seconds = time.perf_counter() - t0
    print(r.stderr, end="")
    if r.returncode != 0:
        fail(f"luz figures exited {r.returncode}")
    print(f"luz figures took {seconds:.1f} s")
    if seconds > LIMIT_SECONDS:
        fail(f"luz figures took {seconds:.1f} s (limit {LIMIT_SECONDS} s)")
    parent = os.path.dirname(os.path.abspath(out))
    left = [n for n in os.listdir(parent) if re.match(r"\.%s\.(tmp|old)-" % re.escape(
        os.path.basename(out)), n)]
    if left:
        fail(f"temporary folders left beside {out}: {left}")
    if not os.path.isfile(os.path.join(out, ".luz-figures")):
        fail("no .luz-figures marker: the next run would refuse to replace the folder")
    page = open(os.path.join(out, "index.html"), encoding="utf-8").read()
    srcs = re.findall(r'<img src="([^"]+)"', page)
    for f in FIGURES:
        if f'id="{f}"' not in page:
            fail(f"index.html has no figure {f}")
        if f"img/{f}.png" not in srcs:
            fail(f"index.html shows no img/{f}.png")
    for s in srcs:
        if s.startswith(("http:", "https:", "/", "file:")):
            fail(f"non-relative image {s}")
        p = os.path.join(out, s)
        if not os.path.isfile(p) or os.path.getsize(p) == 0:
            fail(f"missing image {s}")
    on_disk = {os.path.relpath(p, out) for p in glob.glob(os.path.join(out, "img", "*.png"))}
    if on_disk - set(srcs):
        fail(f"images not on the page: {sorted(on_disk - set(srcs))}")
    for href in re.findall(r'href="(scenes/[^"]+\.(?:json|nff))"', page):
        if not os.path.isfile(os.path.join(out, href)):
            fail(f"scene file {href} not copied")
    if not os.path.isfile(os.path.join(out, "scenes", "bunny.obj")):
        fail("scenes/bunny.obj not copied")
    if re.search(r'(src|href)="(https?:)?//', page):
        fail("the page refers to an external URL")
    # With the web page built into luz (luz web), every JSON scene link has its live twin, and
    # a live link's URL carries a scene's JSON or a built-in scene's name: the page reads nothing
    # else there (docs/WEB.md#url), so an NFF scene (the SPD figure's) has none.
    live = re.findall(r'class="live" href="luz\.html#scene=([^"]+)"', page)
    if os.path.isfile(os.path.join(out, "luz.html")):
        if len(live) < len(re.findall(r'href="scenes/[^"]+\.json"', page)):
            fail(f"only {len(live)} figure scenes link to luz.html")
        for payload in live:
            text = urllib.parse.unquote(html.unescape(payload))
            if not text.startswith("demo:"):
                try:
                    json.loads(text)
                except ValueError as e:
                    fail(f"a live link carries no JSON ({e}): {text[:60]!r}")
    elif live:
        fail("links to luz.html, which was not written")
    for word in ("luz render", "medido / measured"):
        if word not in page:
            fail(f"index.html lacks {word!r}")
    print(f"ok: {len(srcs)} images, {len(FIGURES)} figures")


def chromium(out, shot):
    exe = shutil.which("chromium")
    if not exe:
        fail("chromium is not installed: run scripts/setup.sh (Debian package chromium)")
    page = "file://" + os.path.abspath(os.path.join(out, "index.html"))
    with tempfile.TemporaryDirectory() as profile:
        common = [exe, "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
                  "--no-first-run", "--disable-background-networking",
                  "--disable-component-update", "--disable-sync", "--disable-dev-shm-usage",
                  f"--user-data-dir={profile}", "--enable-logging=stderr", "--v=0",
                  "--virtual-time-budget=10000"]
        r = subprocess.run(common + ["--dump-dom", page], capture_output=True, text=True,
                           timeout=120)
        m = re.search(r'<p id="status">(LUZ-STATUS: [^<]*)</p>', r.stdout)
        if not m:
            fail(f"no status line in the page's DOM (exit {r.returncode}): {r.stderr[-2000:]}")
        status = m.group(1)
        print(status)
        if not status.startswith("LUZ-STATUS: OK") or " broken=0 " not in status:
            fail(f"the page says {status}")
        n = int(re.search(r"images=(\d+)", status).group(1))
        if n < 18:
            fail(f"only {n} images on the page")
        # the page logs nothing itself: any console message (console.error, an uncaught
        # exception, a blocked load) is a failure
        console = [line for line in r.stderr.splitlines() if ":CONSOLE" in line]
        if console:
            fail("console errors:\n" + "\n".join(console))
        os.makedirs(os.path.dirname(os.path.abspath(shot)), exist_ok=True)
        r = subprocess.run(common + ["--hide-scrollbars", "--window-size=1400,3000",
                                     f"--screenshot={os.path.abspath(shot)}", page],
                           capture_output=True, text=True, timeout=120)
        if not os.path.isfile(shot) or os.path.getsize(shot) == 0:
            fail(f"no screenshot written (exit {r.returncode}): {r.stderr[-2000:]}")
    print(f"ok: every image loaded, no console errors; screenshot {shot}")


if __name__ == "__main__":
    if len(sys.argv) == 4 and sys.argv[1] == "run":
        run(sys.argv[2], sys.argv[3])
    elif len(sys.argv) == 4 and sys.argv[1] == "chromium":
        chromium(sys.argv[2], sys.argv[3])
    else:
        fail(__doc__)
