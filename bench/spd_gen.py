#!/usr/bin/env python3
# Three Standard Procedural Databases scenes (Haines' SPD: balls, rings, tree) at any size factor,
# written as NFF and as the POV-Ray 3 file the SPD writes, from the SPD's published algorithms
# (row-vector matrices as the SPD's libvec). usage: spd_gen.py balls|rings|tree [SIZE] [--out DIR]
import argparse
import math
import os

DEFAULT_SIZE = {"balls": 4, "rings": 7, "tree": 11}


# --- 4×4 matrices acting on row vectors (p' = p·M), as the SPD's library ---
def identity():
    return [[1.0 if i == j else 0.0 for j in range(4)] for i in range(4)]


def rotate(axis, angle):
    """Rotation by `angle` about the X (0), Y (1) or Z (2) axis."""
    m = [[0.0] * 4 for _ in range(4)]
    c, s = math.cos(angle), math.sin(angle)
    i, j = [(1, 2), (2, 0), (0, 1)][axis]
    m[axis][axis] = 1.0
    m[i][i] = m[j][j] = c
    m[i][j], m[j][i] = s, -s
    m[3][3] = 1.0
    return m


def rotate_about(a, angle):
    """Rotation by `angle` about the unit axis a."""
    c, s = math.cos(angle), math.sin(angle)
    t = 1.0 - c
    x, y, z = a
    return [[x * x + (1.0 - x * x) * c, x * y * t + z * s, x * z * t - y * s, 0.0],
            [x * y * t - z * s, y * y + (1.0 - y * y) * c, y * z * t + x * s, 0.0],
            [x * z * t + y * s, y * z * t - x * s, z * z + (1.0 - z * z) * c, 0.0],
            [0.0, 0.0, 0.0, 1.0]]


def mul(a, b):
    return [[a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j] + a[i][3] * b[3][j]
             for j in range(4)] for i in range(4)]


def vec(v, m):
    """v·M for a direction (no translation)."""
    return [v[0] * m[0][k] + v[1] * m[1][k] + v[2] * m[2][k] for k in range(3)]


def point(v, m):
    return [v[0] * m[0][k] + v[1] * m[1][k] + v[2] * m[2][k] + m[3][k] for k in range(3)]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def normalized(v):
    d = math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
    return [c / d for c in v] if d > 0.0 else list(v)


def g(x):
    return "%g" % x


# --- the two writers: NFF, and POV-Ray 3 as the SPD writes it ---
class Writers:
    def __init__(self, nff, pov, lights):
        self.nff, self.pov, self.lscale, self.texture = nff, pov, 1.0 / math.sqrt(lights), 0

    def header(self, background, eye, at, up, angle, hither):
        b = background
        self.nff.write(f"b {g(b[0])} {g(b[1])} {g(b[2])}\nv\n")
        for key, v in (("from", eye), ("at", at), ("up", up)):
            self.nff.write(f"{key} {g(v[0])} {g(v[1])} {g(v[2])}\n")
        self.nff.write(f"angle {g(angle)}\nhither {g(hither)}\nresolution 512 512\n")
        self.pov.write("// POV-Ray 3 scene file\n")
        self.pov.write(f"background {{ color red {g(b[0])} green {g(b[1])} blue {g(b[2])} }}\n\n")
        d = normalized([at[k] - eye[k] for k in range(3)])
        size = 2.0 * math.tan(math.radians(angle) / 2.0)  # image plane at distance 1
        right = [-c for c in normalized(cross(up, d))]
        upv = normalized(cross(right, d))
        self.pov.write("camera {\n    location " + self.v(eye) + "\n    direction " + self.v(d) +
                       "\n    right     " + self.v([c * size for c in right]) +
                       "\n    up        " + self.v([c * size for c in upv]) + "\n} // camera\n\n")

    @staticmethod
    def v(p):
        return f"<{g(p[0])}, {g(p[1])}, {g(p[2])}>"

    def light(self, p):
        self.nff.write(f"l {g(p[0])} {g(p[1])} {g(p[2])}\n")
        c = g(self.lscale)
        self.pov.write(f"light_source {{\n    {self.v(p)} color red {c} green {c} blue {c}\n"
                       "} // light\n\n")

    def material(self, colour, ka, kd, ks, phong, angle, kt, ior):
        """The SPD's surface: Ks mirrors and Phong highlights of width `angle` degrees."""
        cos_a = math.cos(math.radians(angle))
        shine = 100000.0 if angle <= 0.0 else math.log(0.5) / math.log(cos_a)
        r, gr, b = (g(c) for c in colour)
        self.nff.write(f"f {r} {gr} {b} {g(kd)} {g(ks)} {g(shine)} {g(kt)} {g(ior)}\n")
        self.texture += 1
        finish = f"        ambient {g(ka)}\n        diffuse {g(kd)}\n"
        if phong > 0.0:
            finish += f"        phong {g(phong)}  phong_size {g(shine)}\n"
        if ks > 0.0:
            finish += f"        reflection {g(ks)}\n"
        self.pov.write(f"#declare txt{self.texture:03d} = texture {{\n    pigment {{\n"
                       f"        color red {r} green {gr} blue {b}\n    }} // pigment\n"
                       "    // normal { bumps, ripples, etc. }\n"
                       f"    finish {{\n{finish}    }} // finish\n}} // texture "
                       f"txt{self.texture:03d}\n\n")

    def quad(self, p):
        self.nff.write("p 4\n" + "".join(f"{g(q[0])} {g(q[1])} {g(q[2])}\n" for q in p))
        for tri in ((p[0], p[2], p[3]), (p[0], p[1], p[2])):
            self.pov.write("object {\n    triangle {\n" +
                           ",\n".join("        " + self.v(q) for q in tri) +
                           "\n    } // tri\n" + f"    texture {{ txt{self.texture:03d} }}\n"
                           "} // object\n\n")

    def sphere(self, c, r):
        self.nff.write(f"s {g(c[0])} {g(c[1])} {g(c[2])} {g(r)}\n")
        self.pov.write(f"sphere {{ {self.v(c)}, {g(r)}  texture {{ txt{self.texture:03d} }} }}\n\n")

    def cone(self, base, rb, apex, ra):
        self.nff.write(f"c {g(base[0])} {g(base[1])} {g(base[2])} {g(rb)} "
                       f"{g(apex[0])} {g(apex[1])} {g(apex[2])} {g(ra)}\n")
        self.pov.write(f"cone {{\n    {self.v(apex)}, {g(ra)},\n    {self.v(base)}, {g(rb)} open\n"
                       f"    texture {{ txt{self.texture:03d} }}\n}}\n\n")


SKY = (0.078, 0.361, 0.753)


# --- balls: the sphereflake, 9 children of a third the radius on every sphere ---
def balls(w, size):
    w.header(SKY, (2.1, 1.3, 1.7), (0.0, 0.0, 0.0), (0.0, 0.0, 1.0), 45.0, 0.01)
    for p in ((4.0, 3.0, 2.0), (1.0, -4.0, 4.0), (-3.0, 1.0, 5.0)):
        w.light(p)
    w.material((1.0, 0.75, 0.33), 0.2, 0.8, 0.0, 0.0, 0.0, 0.0, 1.0)
    w.quad([(12.0, 12.0, -0.5), (-12.0, 12.0, -0.5), (-12.0, -12.0, -0.5), (12.0, -12.0, -0.5)])
    w.material((1.0, 0.9, 0.7), 0.0, 0.5, 0.5, 0.5, 37.0, 0.0, 1.0)
    # the 9 child directions about +Z: a trio tilted up by asin(2/√6), turned by 0, 120, 240°
    h = 1.0 / math.sqrt(2.0)
    tilt = rotate_about(normalized([1.0, -1.0, 0.0]), math.asin(2.0 / math.sqrt(6.0)))
    trio = [vec(d, tilt) for d in ((h, h, 0.0), (h, 0.0, -h), (0.0, h, -h))]
    dirs = [vec(d, rotate(2, k * 2.0 * math.pi / 3.0)) for k in range(3) for d in trio]
    ratio = 1.0 / 3.0

    def flake(depth, c, r, d):
        w.sphere(c, r)
        if depth == 0:
            return
        # along ±Z (also when rounding left |z| a hair below 1 with x = y = 0: no axis to turn
        # about; the SPD's own output takes the flip there)
        if d[2] >= 1.0 or (d[0] == 0.0 and d[1] == 0.0 and d[2] > 0.0):
            m = identity()
        elif d[2] <= -1.0 or (d[0] == 0.0 and d[1] == 0.0):
            m = rotate(1, math.pi)
        else:
            m = rotate_about(normalized(cross([0.0, 0.0, 1.0], d)), math.acos(d[2]))
        scale = r * (1.0 + ratio)
        for e in dirs:
            p = vec(e, m)
            child = [p[k] * scale + c[k] for k in range(3)]
            flake(depth - 1, child, r * ratio, [(child[k] - c[k]) / scale for k in range(3)])

    flake(size, [0.0, 0.0, 0.0], 0.5, [0.0, 0.0, 1.0])


# --- rings: a pyramid of dodecahedral objects, 6 pentagonal rings of spheres and cylinders ---
def rings(w, size):
    radius = 0.07412
    spread = 1.0 / math.sin(math.pi / 8.0)
    eye = (-1.0, -spread, 0.5)
    w.header(SKY, eye, (eye[0], eye[1] + 1.0, eye[2]), (0.0, 0.0, 1.0), 45.0, 1.0)
    for p in ((3.0, -spread, 3.0), (-4.0, -spread, 1.0), (2.0, -spread, -4.0)):
        w.light(p)
    w.material((1.0, 1.0, 1.0), 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    wy = spread * (size + 1)
    wxz = 1.01 * (wy - eye[1]) * math.tan(math.pi / 8.0)
    w.quad([(wxz + eye[0], wy, wxz + eye[2]), (-wxz + eye[0], wy, wxz + eye[2]),
            (-wxz + eye[0], wy, -wxz + eye[2]), (wxz + eye[0], wy, -wxz + eye[2])])
    # the 30 edge midpoints of a dodecahedron: one pentagon in XY, five turned onto its edges
    s = 1.0 / (1.0 + radius)
    dodec = [[s * math.cos(k * 2.0 * math.pi / 5.0), s * math.sin(k * 2.0 * math.pi / 5.0), 0.0]
             for k in range(5)]
    xm = rotate(0, 2.0 * math.acos(math.cos(math.pi / 3.0) / math.sin(math.pi / 5.0)))
    for n in range(1, 6):
        zm = rotate(2, math.pi * (2.0 * (n - 1) + 1.0) / 5.0)
        dodec += [point(point(dodec[k], xm), zm) for k in range(5)]
    colours = [(1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0),
              (0.0, 1.0, 1.0), (1.0, 0.0, 1.0), (1.0, 1.0, 0.0)]
    for depth in range(size):
        oy = spread * (depth + 1)
        for iz in range(depth + 1):
            oz = float(2 * iz - depth)
            for ix in range(depth + 1):
                ox = float(2 * ix - depth)
                for e in range(30):
                    if e % 5 == 0:
                        prev = e + 4
                        w.material(colours[e // 5], 0.0, 0.5, 0.2, 0.3, 37.0, 0.0, 0.0)
                    else:
                        prev = e - 1
                    base = [dodec[e][0] + ox, dodec[e][1] + oy, dodec[e][2] + oz]
                    apex = [dodec[prev][0] + ox, dodec[prev][1] + oy, dodec[prev][2] + oz]
                    w.cone(base, radius, apex, radius)
                    w.sphere(base, radius)


# --- tree: Aono & Kunii's branching, two contracted and turned copies of every branch ---
def tree(w, size):
    w.header(SKY, (4.5, 0.4, 2.0), (0.0, 0.0, 1.5), (0.0, 0.0, 1.0), 45.0, 1.0)
    for p in ((-5.0, 5.0, 50.0), (30.0, -30.0, 30.0), (-40.0, -30.0, 20.0), (10.0, 30.0, 40.0),
              (-30.0, 40.0, 10.0), (50.0, 25.0, 20.0), (-10.0, -60.0, 30.0)):
        w.light(p)
    w.material((0.2, 0.7, 0.2), 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    w.quad([(50.0, 50.0, 0.0), (-50.0, 50.0, 0.0), (-50.0, -50.0, 0.0), (50.0, -50.0, 0.0)])
    w.material((0.55, 0.4, 0.2), 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    taper, width = 0.67, 0.15  # apex/base radius; base radius / length
    branch = []
    for angle, divergence, contraction in ((40.0, 90.0, 0.65), (25.0, 230.0, 0.70)):
        turn = mul(rotate(0, math.radians(angle)), rotate(2, math.radians(divergence)))
        st = identity()
        st[0][0] = st[1][1] = st[2][2] = contraction
        st[3][2] = 1.0
        branch.append(mul(turn, st))

    def grow(m, scale, depth):
        base, apex = point((0.0, 0.0, 0.0), m), point((0.0, 0.0, 1.0), m)
        rb = scale * width
        w.cone(base, rb, apex, rb * taper)
        w.sphere(apex, rb * taper)
        if depth > 0:
            for b in branch:
                grow(mul(b, m), scale * taper, depth - 1)

    grow(identity(), 1.0, size)


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("scene", choices=sorted(DEFAULT_SIZE))
    ap.add_argument("size", type=int, nargs="?", help="the SPD size factor (default: the SPD's)")
    ap.add_argument("--out", default=".", help="folder for SCENE.nff and SCENE.pov")
    a = ap.parse_args()
    size = DEFAULT_SIZE[a.scene] if a.size is None else a.size
    lights = {"balls": 3, "rings": 3, "tree": 7}[a.scene]
    os.makedirs(a.out, exist_ok=True)
    with open(os.path.join(a.out, a.scene + ".nff"), "w") as nff, \
            open(os.path.join(a.out, a.scene + ".pov"), "w") as pov:
        globals()[a.scene](Writers(nff, pov, lights), size)


if __name__ == "__main__":
    main()
