// What the shapes share to place themselves (make_shape) and bound themselves: the columns and
// rows of a transform, ellipse bounds, float padding, the similarity and roundness tests, frames.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/shape.h"
#include "math/bounds.h"
#include "math/transform.h"
#include "scene/shape_desc.h"

namespace luz::shapes {

/// The linear part's column k (the image of the object axis e_k).
inline Vec3 column(const Affine& a, int k) { return {a.m[0][k], a.m[1][k], a.m[2][k]}; }

/// The linear part's row i: the world axis i as a function of object coordinates.
inline Vec3 row(const Affine& a, int i) { return {a.m[i][0], a.m[i][1], a.m[i][2]}; }

/// The translation part: the image of the object origin.
inline Vec3 origin(const Affine& a) { return {a.m[0][3], a.m[1][3], a.m[2][3]}; }

/// The length of column k in double: the placed radius or height along object axis k.
inline double axis_length(const Affine& M, int k) {
    return std::sqrt(double(M.m[0][k]) * M.m[0][k] + double(M.m[1][k]) * M.m[1][k] +
                     double(M.m[2][k]) * M.m[2][k]);
}

/// Bounds of the ellipse {c + cos(φ)·U + sin(φ)·V}: half-extent along world axis i is
/// sqrt(U_i² + V_i²) (the maximum of U_i·cosφ + V_i·sinφ).
inline Bounds3 ellipse_bounds(const Vec3& c, const Vec3& U, const Vec3& V) {
    const Vec3 e{std::sqrt(U.x * U.x + V.x * V.x), std::sqrt(U.y * U.y + V.y * V.y),
                 std::sqrt(U.z * U.z + V.z * V.z)};
    return {c - e, c + e};
}

/// Grows `b` by a few float ulps of its magnitude, so that every point computed in float by
/// the same transform (tessellated vertices, hit points) stays inside despite rounding.
inline Bounds3 pad(Bounds3 b) {
    const float m = std::max(max_component(max(-b.lo, b.hi)), max_component(b.hi - b.lo));
    const Vec3 eps{4.0f * std::numeric_limits<float>::epsilon() * m};
    return {b.lo - eps, b.hi + eps};
}

/// Whether the linear part of `a` is a rotation (or reflection) times a uniform scale: its
/// columns orthogonal and of one length, to a few float ulps.
inline bool is_similarity(const Affine& a) {
    const Vec3 c[3] = {column(a, 0), column(a, 1), column(a, 2)};
    const float l2 = dot(c[0], c[0]);
    const float tol = 16.0f * std::numeric_limits<float>::epsilon() * l2;
    for (int k = 0; k < 3; ++k) {
        if (std::fabs(dot(c[k], c[k]) - l2) > tol) return false;
        if (std::fabs(dot(c[k], c[(k + 1) % 3])) > tol) return false;
    }
    return l2 > 0;
}

/// Whether the linear part keeps a shape around its z axis round: x and y columns of one length,
/// the three columns perpendicular (the height along z free).
inline bool is_round_frame(const Affine& a) {
    const Vec3 U = column(a, 0), V = column(a, 1), W = column(a, 2);
    const float uu = dot(U, U), ww = dot(W, W), uw = std::sqrt(uu * ww);
    const float tol = 16.0f * std::numeric_limits<float>::epsilon();
    return uu > 0 && ww > 0 && std::fabs(dot(V, V) - uu) <= tol * uu &&
           std::fabs(dot(U, V)) <= tol * uu && std::fabs(dot(U, W)) <= tol * uw &&
           std::fabs(dot(V, W)) <= tol * uw;
}

/// The frame whose z axis is `axis` (normalised), x and y any orthonormal completion, scaled by
/// (sx, sy, sz) and moved to `at`.
inline Affine frame_along(const Vec3& axis, float sx, float sy, float sz, const Vec3& at) {
    Vec3 u, v;
    const Vec3 w = normalize(axis);
    orthonormal_basis(w, u, v);
    return from_frame(u * sx, v * sy, w * sz, at);
}

/// Places shape s: transform = the object's user transform · the canonical shape's placement.
inline void set_transform(Shape& s, const ObjectDesc& o, const Affine& placement) {
    s.transform = Transform::from(o.transform * placement);
}

}  // namespace luz::shapes
