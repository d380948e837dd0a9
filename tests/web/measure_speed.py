"""Frames per second of luz.html's full pass (demo:whitted 320×240, one thread) in headless
Chromium, beside `luz render --threads 1`'s render time: python3 measure_speed.py LUZ.HTML LUZ.
The two are measured in turns (a web bench, then a native render, 8 times) and the best of each
kept, so that a machine shared with other work slows both alike."""
import json
import os
import subprocess
import sys
import tempfile

import browser

html, luz = sys.argv[1], sys.argv[2]
frames = 5
b = browser.Browser("file://" + os.path.abspath(html) +
                    "#scene=demo:whitted&set=image.width=320&set=image.height=240")
try:
    b.wait_for("typeof luzPage === 'object'")
    b.evaluate("luzPage.idle()", timeout=120)
    webs, native = [], []
    with tempfile.TemporaryDirectory() as d:
        for _ in range(8):
            webs.append(b.evaluate(f"luzPage.bench({frames})", timeout=300))
            stats = os.path.join(d, "stats.json")
            subprocess.run([luz, "render", "demo:whitted", "--width", "320", "--height", "240",
                            "--threads", "1", "--stats", stats, "-o", os.path.join(d, "x.png")],
                           check=True, capture_output=True)
            native.append(json.load(open(stats))["seconds"] * 1000)
finally:
    b.close()
web, n = min(webs), min(native)
print(f"web: {web:.1f} ms a frame ({1000 / web:.1f} fps); native --threads 1: {n:.1f} ms "
      f"({1000 / n:.1f} fps); web/native time: {web / n:.2f}; page {os.path.getsize(html)} bytes")
