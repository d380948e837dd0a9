// Tessellation of the canonical shapes (shape.h) into world-space triangles with analytic
// normals, watertight for closed shapes, and their exact surface areas.
#include "geometry/tessellate.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace luz {

namespace {

constexpr double pi = std::numbers::pi;

/// Appends vertices and triangles of one shape: object-space positions and normals go in,
/// world-space ones come out. A mirroring transform (negative determinant) turns
/// counter-clockwise into clockwise, so the winding is reversed to stay counter-clockwise
/// seen from outside.
class Emitter {
  public:
    Emitter(const Transform& t, TriangleMesh& out)
        : t_(t), out_(out), flip_(t.world_from_object.determinant() < 0) {}

    /// Adds a vertex at object point p with object normal n (any length); returns its index.
    uint32_t vertex(const Vec3& p, const Vec3& n) {
        out_.positions.push_back(t_.point(p));
        out_.normals.push_back(normalize(t_.normal(n)));
        return static_cast<uint32_t>(out_.positions.size() - 1);
    }
    /// Adds triangle (a, b, c), counter-clockwise from outside in object space.
    void triangle(uint32_t a, uint32_t b, uint32_t c) {
        out_.indices.push_back(a);
        out_.indices.push_back(flip_ ? c : b);
        out_.indices.push_back(flip_ ? b : c);
    }
    /// Adds quad (a, b, c, d), counter-clockwise from outside, as triangles (a,b,c), (a,c,d).
    void quad(uint32_t a, uint32_t b, uint32_t c, uint32_t d) {
        triangle(a, b, c);
        triangle(a, c, d);
    }
    void reserve(size_t vertices, size_t triangles) {
        out_.positions.reserve(out_.positions.size() + vertices);
        out_.normals.reserve(out_.normals.size() + vertices);
        out_.indices.reserve(out_.indices.size() + 3 * triangles);
    }

  private:
    const Transform& t_;
    TriangleMesh& out_;
    bool flip_;
};

/// cos and sin of 2π·j/n for j = 0 … n−1, computed once so that every vertex on the same
/// circle (side rims and cap rims, seams) uses the very same float values.
struct Circle {
    std::vector<float> c, s;
    explicit Circle(int n) : c(n), s(n) {
        for (int j = 0; j < n; ++j) {
            const double phi = 2.0 * pi * j / n;
            c[j] = static_cast<float>(std::cos(phi));
            s[j] = static_cast<float>(std::sin(phi));
        }
    }
};

/// Unit sphere: `level` segments around z, level/2 rings from the pole z = 1 (θ = 0) to the
/// pole z = −1 (θ = π); each pole is one vertex, so no triangle is degenerate.
void sphere(Emitter& e, int level) {
    const int n = level, rings = std::max(2, level / 2);
    const Circle circle(n);
    e.reserve(size_t(n) * (rings - 1) + 2, size_t(2) * n * (rings - 1));
    const uint32_t north = e.vertex({0, 0, 1}, {0, 0, 1});
    const uint32_t south = e.vertex({0, 0, -1}, {0, 0, -1});
    // ring(i, j): vertex of ring i (1 … rings−1) at segment j (mod n).
    std::vector<uint32_t> ring(size_t(n) * (rings - 1));
    for (int i = 1; i < rings; ++i) {
        const double theta = pi * i / rings;
        const float st = static_cast<float>(std::sin(theta)),
                    ct = static_cast<float>(std::cos(theta));
        for (int j = 0; j < n; ++j) {
            const Vec3 p{st * circle.c[j], st * circle.s[j], ct};
            ring[size_t(i - 1) * n + j] = e.vertex(p, p);
        }
    }
    auto at = [&](int i, int j) { return ring[size_t(i - 1) * n + (j % n)]; };
    // Going down θ then around φ is counter-clockwise from outside (θ̂ × φ̂ = r̂).
    for (int j = 0; j < n; ++j) {
        e.triangle(north, at(1, j), at(1, j + 1));
        for (int i = 1; i + 1 < rings; ++i)
            e.quad(at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
        e.triangle(at(rings - 1, j), south, at(rings - 1, j + 1));
    }
}

/// Box [lo, hi]: 6 faces of 4 vertices with the face normal, 2 triangles each.
void box(Emitter& e, const Vec3& lo, const Vec3& hi) {
    e.reserve(24, 12);
    for (int axis = 0; axis < 3; ++axis) {
        // (u, v, axis) is a right-handed permutation of (x, y, z).
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        for (int side = 0; side < 2; ++side) {
            Vec3 n{0.0f};
            n[axis] = side ? 1.0f : -1.0f;
            auto corner = [&](int a, int b) {
                Vec3 p;
                p[axis] = side ? hi[axis] : lo[axis];
                p[u] = a ? hi[u] : lo[u];
                p[v] = b ? hi[v] : lo[v];
                return e.vertex(p, n);
            };
            const uint32_t p00 = corner(0, 0), p10 = corner(1, 0), p11 = corner(1, 1),
                           p01 = corner(0, 1);
            // û × v̂ = axis: counter-clockwise from outside on the + side, reversed on the − side.
            if (side)
                e.quad(p00, p10, p11, p01);
            else
                e.quad(p00, p01, p11, p10);
        }
    }
}

/// A disc cap at height z of the unit circle, as a fan from its centre sharing the rim
/// positions (the same Circle values) of the side; `up` is the outward normal's direction.
void cap(Emitter& e, const Circle& circle, float z, bool up) {
    const int n = static_cast<int>(circle.c.size());
    const Vec3 nz{0, 0, up ? 1.0f : -1.0f};
    const uint32_t centre = e.vertex({0, 0, z}, nz);
    const uint32_t first = centre + 1;  // rim vertex j is first + j
    for (int j = 0; j < n; ++j) e.vertex({circle.c[j], circle.s[j], z}, nz);
    for (int j = 0; j < n; ++j) {
        const uint32_t a = first + j, b = first + (j + 1) % n;
        if (up)
            e.triangle(centre, a, b);
        else
            e.triangle(centre, b, a);
    }
}

/// Cylinder of radius 1 around z, z ∈ [0, 1]: one segment along the side (normals are
/// constant along it), optional caps.
void cylinder(Emitter& e, int level, bool caps) {
    const int n = level;
    const Circle circle(n);
    e.reserve(2 * size_t(n) + (caps ? 2 * size_t(n + 1) : 0), 2 * size_t(n) + (caps ? 2 * n : 0));
    uint32_t bottom = 0;
    for (int j = 0; j < n; ++j) {
        const Vec3 nr{circle.c[j], circle.s[j], 0};
        const uint32_t b = e.vertex({circle.c[j], circle.s[j], 0}, nr);
        e.vertex({circle.c[j], circle.s[j], 1}, nr);
        if (j == 0) bottom = b;
    }
    // Vertex (j, 0) is bottom + 2j, (j, 1) is bottom + 2j + 1; φ̂ × ẑ = r̂.
    for (int j = 0; j < n; ++j) {
        const uint32_t a = bottom + 2 * j, b = bottom + 2 * ((j + 1) % n);
        e.quad(a, b, b + 1, a + 1);
    }
    if (caps) {
        cap(e, circle, 0.0f, false);
        cap(e, circle, 1.0f, true);
    }
}

/// Cone of radius 1 − z around z, z ∈ [0, 1]: the side as one triangle per segment from the
/// base rim to the apex. The normal at the apex is undefined, so each segment has its own
/// apex vertex (same position) with the normal of the segment's mid-angle.
void cone(Emitter& e, int level, bool caps) {
    const int n = level;
    const Circle circle(n);
    e.reserve(2 * size_t(n) + (caps ? size_t(n + 1) : 0), size_t(n) + (caps ? n : 0));
    // Side normal ∝ ∇(√(x²+y²) + z − 1) = (cosφ, sinφ, 1).
    std::vector<uint32_t> rim(n);
    for (int j = 0; j < n; ++j)
        rim[j] = e.vertex({circle.c[j], circle.s[j], 0}, {circle.c[j], circle.s[j], 1});
    for (int j = 0; j < n; ++j) {
        const double mid = 2.0 * pi * (j + 0.5) / n;
        const uint32_t apex = e.vertex(
            {0, 0, 1}, {static_cast<float>(std::cos(mid)), static_cast<float>(std::sin(mid)), 1});
        // φ̂ × (ẑ − r̂) = r̂ + ẑ: outward.
        e.triangle(rim[j], rim[(j + 1) % n], apex);
    }
    if (caps) cap(e, circle, 0.0f, false);
}

/// Torus of major radius 1 around z and minor radius r: `level` segments around the major
/// circle (angle u), max(3, level/2) around the tube (angle v);
/// p = ((1 + r·cos v)·cos u, (1 + r·cos v)·sin u, r·sin v), n = (cos v·cos u, cos v·sin u, sin v).
void torus(Emitter& e, int level, float r) {
    const int nu = level, nv = std::max(3, level / 2);
    const Circle cu(nu), cv(nv);
    e.reserve(size_t(nu) * nv, 2 * size_t(nu) * nv);
    uint32_t first = 0;
    for (int j = 0; j < nu; ++j) {
        for (int k = 0; k < nv; ++k) {
            const float rho = 1.0f + r * cv.c[k];
            const uint32_t i = e.vertex({rho * cu.c[j], rho * cu.s[j], r * cv.s[k]},
                                        {cv.c[k] * cu.c[j], cv.c[k] * cu.s[j], cv.s[k]});
            if (j == 0 && k == 0) first = i;
        }
    }
    auto at = [&](int j, int k) { return first + uint32_t((j % nu) * nv + (k % nv)); };
    // ∂p/∂u × ∂p/∂v ∝ n: around the major circle first, then around the tube.
    for (int j = 0; j < nu; ++j)
        for (int k = 0; k < nv; ++k) e.quad(at(j, k), at(j + 1, k), at(j + 1, k + 1), at(j, k + 1));
}

/// One triangle; its normal is that of its winding, (v1 − v0) × (v2 − v0).
void triangle(Emitter& e, const Vec3 (&v)[3]) {
    const Vec3 n = cross(v[1] - v[0], v[2] - v[0]);
    const uint32_t a = e.vertex(v[0], n), b = e.vertex(v[1], n), c = e.vertex(v[2], n);
    e.triangle(a, b, c);
}

/// A mesh's own triangles (already world space). Smooth: its shared vertices and normals; flat:
/// three vertices per triangle carrying the face normal, so interpolation keeps it constant.
void mesh_triangles(const Mesh& m, TriangleMesh& out) {
    const uint32_t base = static_cast<uint32_t>(out.positions.size());
    if (m.smooth()) {
        out.positions.insert(out.positions.end(), m.positions.begin(), m.positions.end());
        for (const Vec3& n : m.normals) out.normals.push_back(n == Vec3{0.0f} ? Vec3{0, 0, 1} : n);
        for (uint32_t i : m.indices) out.indices.push_back(base + i);
        return;
    }
    out.positions.reserve(out.positions.size() + m.indices.size());
    out.normals.reserve(out.normals.size() + m.indices.size());
    for (size_t t = 0; t < m.triangle_count(); ++t) {
        Vec3 p[3];
        m.vertices(t, p[0], p[1], p[2]);
        const Vec3 n = m.face_normal(t);
        for (int k = 0; k < 3; ++k) {
            out.indices.push_back(static_cast<uint32_t>(out.positions.size()));
            out.positions.push_back(p[k]);
            out.normals.push_back(n);
        }
    }
}

}  // namespace

void tessellate(const Shape& s, int level, TriangleMesh& out) {
    if (s.type == ShapeType::mesh) {
        if (s.mesh) mesh_triangles(*s.mesh, out);
        return;
    }
    level = std::max(3, level);
    Emitter e(s.transform, out);
    switch (s.type) {
        case ShapeType::sphere:
            sphere(e, level);
            break;
        case ShapeType::box:
            box(e, s.lo, s.hi);
            break;
        case ShapeType::cylinder:
            cylinder(e, level, s.caps);
            break;
        case ShapeType::cone:
            cone(e, level, s.caps);
            break;
        case ShapeType::torus:
            torus(e, level, s.minor);
            break;
        case ShapeType::plane:
            break;  // drawn by the rasterizer as a quad clipped to the view
        case ShapeType::triangle:
            triangle(e, s.vertices);
            break;
        case ShapeType::mesh:
            break;  // above
    }
}

double analytic_area(const Shape& s) {
    // With a similarity transform, the image of object axis k has length |column k|: the
    // placed radii and heights (shape.cpp) times the user's uniform scale.
    const Affine& M = s.transform.world_from_object;
    auto col = [&](int k) {
        return std::sqrt(double(M.m[0][k]) * M.m[0][k] + double(M.m[1][k]) * M.m[1][k] +
                         double(M.m[2][k]) * M.m[2][k]);
    };
    const double r = 0.5 * (col(0) + col(1)), h = col(2);
    switch (s.type) {
        case ShapeType::sphere:
            return 4.0 * pi * r * r;  // 4πr²
        case ShapeType::box: {
            const double a = col(0) * (double(s.hi.x) - s.lo.x),
                         b = col(1) * (double(s.hi.y) - s.lo.y),
                         c = col(2) * (double(s.hi.z) - s.lo.z);
            return 2.0 * (a * b + b * c + c * a);
        }
        case ShapeType::cylinder:
            return 2.0 * pi * r * h + (s.caps ? 2.0 * pi * r * r : 0.0);  // 2πrh + 2πr²
        case ShapeType::cone:
            return pi * r * std::sqrt(r * r + h * h) +
                   (s.caps ? pi * r * r : 0.0);  // πr·slant + πr²
        case ShapeType::torus:
            return 4.0 * pi * pi * r * (s.minor * r);  // 4π²Rr
        case ShapeType::plane:
            return std::numeric_limits<double>::infinity();
        case ShapeType::triangle: {
            const Vec3 a = s.transform.point(s.vertices[0]), b = s.transform.point(s.vertices[1]),
                       c = s.transform.point(s.vertices[2]);
            return 0.5 * double(length(cross(b - a, c - a)));
        }
        case ShapeType::mesh:
            break;
    }
    throw std::logic_error("analytic_area: mesh shapes are not supported yet");
}

}  // namespace luz
