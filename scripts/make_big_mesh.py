#!/usr/bin/env python3
"""Writes a large triangle mesh as Wavefront OBJ, for benchmarks: a sphere with bumps
(r = 1 + ripples in latitude and longitude), N segments around and N/2 rings, one vertex at
each pole, smooth and closed, counter-clockwise from outside: N·(N/2 − 1)·2 triangles
(N = 1024: 1 046 528 triangles, about 45 MB).

    python3 scripts/make_big_mesh.py [N] > scenes/bigmesh.obj
    luz render scenes/bigmesh.json --stats stats.json
"""
import math
import sys


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 1024
    if n < 8 or n % 2:
        sys.exit("make_big_mesh.py: N must be an even number >= 8")
    rings = n // 2
    out = sys.stdout
    write = out.write
    tris = n * (rings - 1) * 2
    write(f"# luz scripts/make_big_mesh.py {n}: a bumpy sphere, {tris} triangles\n")
    # vertices: the north pole, then rings 1 .. rings-1 of n vertices, then the south pole
    def radius(th, ph):
        return 1.0 + 0.04 * math.sin(12 * th) * math.sin(15 * ph) + 0.015 * math.sin(60 * th + 3 * ph)

    write("v 0 %.6f 0\n" % radius(0.0, 0.0))
    lines = []
    for j in range(1, rings):
        th = math.pi * j / rings
        st, ct = math.sin(th), math.cos(th)
        for i in range(n):
            ph = 2 * math.pi * i / n
            r = radius(th, ph)
            lines.append("v %.6f %.6f %.6f\n" % (r * st * math.cos(ph), r * ct, r * st * math.sin(ph)))
        write("".join(lines))
        lines.clear()
    south = 1 + (rings - 1) * n + 1  # 1-based
    write("v 0 %.6f 0\n" % -radius(math.pi, 0.0))

    def at(i, j):  # 1-based index of vertex i (mod n) on ring j (1 .. rings-1)
        return 2 + (j - 1) * n + (i % n)

    # faces, counter-clockwise seen from outside (y up, φ from +x towards +z)
    for i in range(n):
        lines.append("f 1 %d %d\n" % (at(i + 1, 1), at(i, 1)))
    write("".join(lines))
    lines.clear()
    for j in range(1, rings - 1):
        for i in range(n):
            a, b, c, d = at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)
            lines.append("f %d %d %d\nf %d %d %d\n" % (a, b, c, a, c, d))
        write("".join(lines))
        lines.clear()
    for i in range(n):
        lines.append("f %d %d %d\n" % (south, at(i, rings - 1), at(i + 1, rings - 1)))
    write("".join(lines))


if __name__ == "__main__":
    main()
