#!/usr/bin/env python3
# The SPD's own check (docs/SCENES.md#nff, issue 39 item 3): each of the seven Standard Procedural
# Databases scenes rendered by its testing procedure — 512², rays through the 513×513 pixel
# corners (adaptive antialiasing whose threshold refines nothing), max_depth 4 (the SPD's depth 5
# counting the eye ray) — and luz's --stats ray counts compared with the SPD's published ones.
#   spd_check.py LUZ SCENES_DIR WORK_DIR   (exit 1 when a count is off by more than 10 %)
import json
import math
import pathlib
import subprocess
import sys
import time

# SPD 3.14 README: eye rays that hit, reflected, refracted, shadow rays.
PUBLISHED = {
    "balls": (263169, 175095, 0, 954368),
    "gears": (245086, 304643, 207564, 2246955),
    "mount": (173125, 354769, 354769, 412922),
    "rings": (263169, 315236, 0, 1085002),
    "teapot": (161120, 225248, 0, 407656),
    "tetra": (49788, 0, 0, 46112),
    "tree": (169836, 0, 0, 1097419),
}
KINDS = ("eye hits", "reflected", "refracted", "shadow")
TOLERANCE = 0.10


def run(luz, args, cwd):
    r = subprocess.run([luz, *args, "--quiet"], cwd=cwd, capture_output=True, timeout=600)
    if r.returncode != 0:
        sys.exit(f"luz {' '.join(args)}: exit {r.returncode}: {r.stderr.decode()}")


def read_pfm(path):
    """A PFM file's values, row-major, as a flat list of floats."""
    import struct
    data = pathlib.Path(path).read_bytes()
    fields, pos = [], 0
    while len(fields) < 4:
        while data[pos:pos + 1].isspace():
            pos += 1
        end = pos
        while not data[end:end + 1].isspace():
            end += 1
        fields.append(data[pos:end].decode())
        pos = end
    pos += 1
    channels = 3 if fields[0] == "PF" else 1
    n = int(fields[1]) * int(fields[2]) * channels
    order = "<" if float(fields[3]) < 0 else ">"
    return struct.unpack(f"{order}{n}f", data[pos:pos + 4 * n]), channels


def transmitting_without_reflection(scene):
    """The names luz gives (f1, f2, … in order of first appearance) to the scene's materials
    with T > 0 and Ks = 0: the SPD spawns a reflected ray at every transmitting hit, luz only
    where the reflection coefficient Ks is > 0."""
    names, found = {}, []
    for line in scene.read_text().splitlines():
        if line.startswith("f "):
            f = tuple(float(x) for x in line.split()[1:])
            if f not in names:
                names[f] = f"f{len(names) + 1}"
                if f[6] > 0 and f[4] == 0:
                    found.append(names[f])
    return found


def counts(luz, scene, work, extra=()):
    """luz's counts for `scene`: (eye rays that hit, reflected, refracted, shadow), and the
    render's time and primary rays."""
    stats = work / f"{scene.stem}.json"
    start = time.monotonic()
    run(luz, ["render", str(scene), "--width", "512", "--height", "512", "--aa", "adaptive",
              "--threshold", "1", "--stats", str(stats), "-o", str(work / f"{scene.stem}.png"),
              *extra], work)
    seconds = time.monotonic() - start
    s = json.loads(stats.read_text())
    rays = s["rays"]
    # --stats counts every eye ray: those that hit are counted in the depth image of the same
    # rays — a 513² render whose pixel centres are the 512² render's corners: the SPD scenes'
    # fov_y is 2·atan(tan(22.5°)·512/511) (angle 45 over 512 rows), so 513 centres span
    # 2·atan(tan(22.5°)·513/511).
    fov = 2 * math.degrees(math.atan(math.tan(math.radians(22.5)) * 513 / 511))
    depth = work / f"{scene.stem}-corners.pfm"
    run(luz, ["render", str(scene), "--width", "513", "--height", "513", "--set",
              f"camera.fov_y={fov!r}", "--set", "render.max_depth=0", "--aov", "depth",
              "-o", str(depth)], work)
    values, channels = read_pfm(work / f"{scene.stem}-corners.depth.pfm")
    hits = sum(1 for v in values[::channels] if math.isfinite(v))
    return (hits, rays["reflection"], rays["refraction"], rays["shadow"]), seconds, rays["primary"]


def main():
    luz, scenes_dir, work = sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])
    work.mkdir(parents=True, exist_ok=True)
    failures = []
    print("| scene | " + " | ".join(f"{k} luz / SPD" for k in KINDS) + " | eye rays | time |")
    print("|---" * (len(KINDS) + 3) + "|")
    for name, published in PUBLISHED.items():
        scene = scenes_dir / f"{name}.nff"
        mine, seconds, primary = counts(luz, scene, work)
        rule = transmitting_without_reflection(scene)
        if rule:
            # The SPD's rule, without changing the picture visibly: those materials reflect
            # 1e-6, so that luz spawns the reflected rays the SPD counts (gears' glass).
            extra = [a for n in rule for a in ("--set", f"materials.{n}.reflection=1e-6")]
            print(f"| {name} (luz's rule: no reflected ray where Ks = 0) | " +
                  " | ".join(f"{a} / {b}" for a, b in zip(mine, published)) +
                  f" | {primary} | {seconds:.2f} s |")
            mine, seconds, primary = counts(luz, scene, work, extra)
            name += f" (reflection 1e-6 on {len(rule)} glass materials)"
        cells = []
        for kind, a, b in zip(KINDS, mine, published):
            off = abs(a - b) / b if b else (0 if a == 0 else math.inf)
            cells.append(f"{a} / {b} ({100 * (a - b) / b:+.1f} %)" if b else f"{a} / {b}")
            if off > TOLERANCE:
                failures.append(f"{name}: {kind}: luz {a}, SPD {b}")
        print(f"| {name} | " + " | ".join(cells) + f" | {primary} | {seconds:.2f} s |")
    if failures:
        print("off by more than 10 %:\n  " + "\n  ".join(failures))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
