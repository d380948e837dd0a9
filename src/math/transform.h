// Transform: an affine map (3×4 matrix) with its inverse, for points, vectors and normals.
// Names follow DESIGN.md: a transform is named by what it maps to and from (world_from_object).
#pragma once

#include <cmath>
#include <numbers>

#include "luz/affine.h"
#include "luz/vec3.h"
#include "math/bounds.h"
#include "math/ray.h"

namespace luz {

/// a·b (apply b first).
constexpr Affine operator*(const Affine& a, const Affine& b) {
    Affine r;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 4; ++j) {
            float s = (j == 3) ? a.m[i][3] : 0.0f;
            for (int k = 0; k < 3; ++k) s += a.m[i][k] * b.m[k][j];
            r.m[i][j] = s;
        }
    }
    return r;
}

/// The inverse of an invertible affine map (computed in double for accuracy).
inline Affine inverse(const Affine& a) {
    const double m00 = a.m[0][0], m01 = a.m[0][1], m02 = a.m[0][2];
    const double m10 = a.m[1][0], m11 = a.m[1][1], m12 = a.m[1][2];
    const double m20 = a.m[2][0], m21 = a.m[2][1], m22 = a.m[2][2];
    const double c00 = m11 * m22 - m12 * m21, c01 = m02 * m21 - m01 * m22,
                 c02 = m01 * m12 - m02 * m11;
    const double c10 = m12 * m20 - m10 * m22, c11 = m00 * m22 - m02 * m20,
                 c12 = m02 * m10 - m00 * m12;
    const double c20 = m10 * m21 - m11 * m20, c21 = m01 * m20 - m00 * m21,
                 c22 = m00 * m11 - m01 * m10;
    const double inv_det = 1.0 / (m00 * c00 + m01 * c10 + m02 * c20);
    const double l[3][3] = {{c00, c01, c02}, {c10, c11, c12}, {c20, c21, c22}};
    Affine r;
    for (int i = 0; i < 3; ++i) {
        double t = 0;
        for (int k = 0; k < 3; ++k) {
            r.m[i][k] = static_cast<float>(l[i][k] * inv_det);
            t += l[i][k] * inv_det * a.m[k][3];
        }
        r.m[i][3] = static_cast<float>(-t);
    }
    return r;
}

constexpr Affine translation(const Vec3& t) {
    Affine a;
    a.m[0][3] = t.x;
    a.m[1][3] = t.y;
    a.m[2][3] = t.z;
    return a;
}
constexpr Affine scaling(const Vec3& s) {
    Affine a;
    a.m[0][0] = s.x;
    a.m[1][1] = s.y;
    a.m[2][2] = s.z;
    return a;
}
/// Rotation by `degrees` about coordinate axis `axis` (0 = x, 1 = y, 2 = z), right-hand rule.
inline Affine rotation(int axis, float degrees) {
    const double r = degrees * std::numbers::pi / 180.0;
    const float c = static_cast<float>(std::cos(r)), s = static_cast<float>(std::sin(r));
    const int i = (axis + 1) % 3, j = (axis + 2) % 3;
    Affine a;
    a.m[i][i] = c;
    a.m[i][j] = -s;
    a.m[j][i] = s;
    a.m[j][j] = c;
    return a;
}
/// Columns u, v, w and origin o: maps (x, y, z) to o + x·u + y·v + z·w.
constexpr Affine from_frame(const Vec3& u, const Vec3& v, const Vec3& w, const Vec3& o) {
    Affine a;
    for (int i = 0; i < 3; ++i) {
        a.m[i][0] = u[i];
        a.m[i][1] = v[i];
        a.m[i][2] = w[i];
        a.m[i][3] = o[i];
    }
    return a;
}

/// An affine map together with its inverse.
struct Transform {
    Affine world_from_object;
    Affine object_from_world;

    static Transform from(const Affine& a) { return {a, inverse(a)}; }

    Vec3 point(const Vec3& p) const { return world_from_object.point(p); }
    Vec3 vector(const Vec3& v) const { return world_from_object.vector(v); }
    /// Object-space normal to world space by the inverse transpose (not normalised).
    Vec3 normal(const Vec3& n) const { return object_from_world.transpose_vector(n); }
    Ray to_object(const Ray& r) const {
        return {object_from_world.point(r.origin), object_from_world.vector(r.direction)};
    }
    Bounds3 bounds(const Bounds3& b) const {
        Bounds3 out;
        for (int i = 0; i < 8; ++i) out.expand(point(b.corner(i)));
        return out;
    }
};

/// A unit vector and two unit vectors perpendicular to it and each other (u × v = w).
inline void orthonormal_basis(const Vec3& w, Vec3& u, Vec3& v) {
    const Vec3 a = std::fabs(w.x) > 0.9f ? Vec3{0, 1, 0} : Vec3{1, 0, 0};
    u = normalize(cross(a, w));
    v = cross(w, u);
}

}  // namespace luz
