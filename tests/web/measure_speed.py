"""Frames per second of luz.html's full pass (demo:whitted 320×240, one thread) in headless
Chromium, beside `luz render --threads 1`'s render time: python3 measure_speed.py LUZ.HTML LUZ."""
import json
import os
import subprocess
import sys
import tempfile

import browser

html, luz = sys.argv[1], sys.argv[2]
frames = 20
b = browser.Browser("file://" + os.path.abspath(html) +
                    "#scene=demo:whitted&set=image.width=320&set=image.height=240")
try:
    b.wait_for("typeof luzPage === 'object'")
    b.evaluate("luzPage.idle()", timeout=120)
    web = min(b.evaluate(f"luzPage.bench({frames})", timeout=300) for _ in range(3))
finally:
    b.close()
native = []
with tempfile.TemporaryDirectory() as d:
    for _ in range(5):
        stats = os.path.join(d, "stats.json")
        subprocess.run([luz, "render", "demo:whitted", "--width", "320", "--height", "240",
                        "--threads", "1", "--stats", stats, "-o", os.path.join(d, "x.png")],
                       check=True, capture_output=True)
        native.append(json.load(open(stats))["seconds"] * 1000)
n = min(native)
print(f"web: {web:.1f} ms a frame ({1000 / web:.1f} fps); native --threads 1: {n:.1f} ms "
      f"({1000 / n:.1f} fps); web/native time: {web / n:.2f}; page {os.path.getsize(html)} bytes")
