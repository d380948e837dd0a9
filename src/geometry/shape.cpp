// Shape construction: the canonical shape of each object type, its placement transform, and
// tight world-space bounds (see shape.h for the canonical object spaces).
#include "geometry/shape.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace luz {

namespace {

/// The linear part's column k (the image of the object axis e_k).
Vec3 column(const Affine& a, int k) { return {a.m[0][k], a.m[1][k], a.m[2][k]}; }

/// The linear part's row i: the world axis i as a function of object coordinates.
Vec3 row(const Affine& a, int i) { return {a.m[i][0], a.m[i][1], a.m[i][2]}; }

/// Bounds of the ellipse {c + cos(φ)·U + sin(φ)·V}: half-extent along world axis i is
/// sqrt(U_i² + V_i²) (the maximum of U_i·cosφ + V_i·sinφ).
Bounds3 ellipse_bounds(const Vec3& c, const Vec3& U, const Vec3& V) {
    const Vec3 e{std::sqrt(U.x * U.x + V.x * V.x), std::sqrt(U.y * U.y + V.y * V.y),
                 std::sqrt(U.z * U.z + V.z * V.z)};
    return {c - e, c + e};
}

/// Grows `b` by a few float ulps of its magnitude, so that every point computed in float by
/// the same transform (tessellated vertices, hit points) stays inside despite rounding.
Bounds3 pad(Bounds3 b) {
    const float m = std::max(max_component(max(-b.lo, b.hi)), max_component(b.hi - b.lo));
    const Vec3 eps{4.0f * std::numeric_limits<float>::epsilon() * m};
    return {b.lo - eps, b.hi + eps};
}

/// Whether the linear part of `a` is a rotation (or reflection) times a uniform scale: its
/// columns orthogonal and of one length, to a few float ulps.
bool is_similarity(const Affine& a) {
    const Vec3 c[3] = {column(a, 0), column(a, 1), column(a, 2)};
    const float l2 = dot(c[0], c[0]);
    const float tol = 16.0f * std::numeric_limits<float>::epsilon() * l2;
    for (int k = 0; k < 3; ++k) {
        if (std::fabs(dot(c[k], c[k]) - l2) > tol) return false;
        if (std::fabs(dot(c[k], c[(k + 1) % 3])) > tol) return false;
    }
    return l2 > 0;
}

/// Fills the shape's world-space form (shape.h) where it exists.
void set_world_form(Shape& s) {
    const Affine& M = s.transform.world_from_object;
    const Vec3 origin{M.m[0][3], M.m[1][3], M.m[2][3]};
    if (s.type == ShapeType::sphere && is_similarity(M)) {
        s.world_form = true;
        s.centre = origin;
        s.radius = length(column(M, 0));
    } else if (s.type == ShapeType::plane) {
        // the object normal +z by the inverse transpose, as surface_at() gives it
        const Vec3 n = s.transform.normal({0, 0, 1});
        const float l = length(n);
        if (l > 0 && std::isfinite(l)) {
            s.world_form = true;
            s.normal = n / l;
            s.offset = dot(s.normal, origin);
        }
    }
}

}  // namespace

Shape make_shape(const ObjectDesc& o, int object_index) {
    Shape s;
    s.type = o.type;
    s.material = o.material;
    s.object = object_index;

    // placement: canonical object space → the object as its own keys define it (shape.h).
    Affine placement;
    switch (o.type) {
        case ShapeType::sphere:
            placement = translation(o.center) * scaling(Vec3{o.radius});
            break;
        case ShapeType::box:
            s.lo = min(o.min, o.max);
            s.hi = max(o.min, o.max);
            break;
        case ShapeType::cylinder:
        case ShapeType::cone: {
            Vec3 u, v;
            const Vec3 w = normalize(o.axis);
            orthonormal_basis(w, u, v);
            placement = from_frame(u * o.radius, v * o.radius, w * o.height, o.base);
            s.caps = o.caps;
            break;
        }
        case ShapeType::torus: {
            Vec3 u, v;
            const Vec3 a = normalize(o.axis);
            orthonormal_basis(a, u, v);
            const float R = o.major_radius;
            placement = from_frame(u * R, v * R, a * R, o.center);
            s.minor = o.minor_radius / o.major_radius;
            break;
        }
        case ShapeType::plane: {
            Vec3 u, v;
            const Vec3 n = normalize(o.normal);
            orthonormal_basis(n, u, v);
            placement = from_frame(u, v, n, o.point);
            break;
        }
        case ShapeType::triangle:
            for (int k = 0; k < 3; ++k) s.vertices[k] = o.vertices[k];
            break;
        case ShapeType::mesh:
            s.mesh = std::make_shared<const Mesh>(build_mesh(o));
            return s;  // world space already: identity transform
    }
    s.transform = Transform::from(o.transform * placement);
    set_world_form(s);
    return s;
}

Bounds3 bounds(const Shape& s) {
    const Affine& M = s.transform.world_from_object;
    const Vec3 origin{M.m[0][3], M.m[1][3], M.m[2][3]};
    Bounds3 b;
    switch (s.type) {
        case ShapeType::sphere: {
            // The unit ball's image is an ellipsoid; its half-extent along world axis i is
            // |row_i| (the maximum of row_i·p over |p| = 1). Exact for every affine map.
            const Vec3 e{length(row(M, 0)), length(row(M, 1)), length(row(M, 2))};
            b = {origin - e, origin + e};
            break;
        }
        case ShapeType::box:
            b = s.transform.bounds(Bounds3{s.lo, s.hi});
            break;
        case ShapeType::cylinder: {
            // The two rims (ellipses in world space) bound the whole cylinder.
            const Vec3 U = column(M, 0), V = column(M, 1), W = column(M, 2);
            b = ellipse_bounds(origin, U, V);
            b.expand(ellipse_bounds(origin + W, U, V));
            break;
        }
        case ShapeType::cone: {
            // The base rim and the apex.
            const Vec3 U = column(M, 0), V = column(M, 1), W = column(M, 2);
            b = ellipse_bounds(origin, U, V);
            b.expand(origin + W);
            break;
        }
        case ShapeType::torus: {
            // The major circle's bounds grown by the tube's (an ellipsoid of radius `minor`):
            // exact for similarity transforms, conservative otherwise.
            const Vec3 U = column(M, 0), V = column(M, 1);
            b = ellipse_bounds(origin, U, V);
            const Vec3 e = Vec3{length(row(M, 0)), length(row(M, 1)), length(row(M, 2))} * s.minor;
            b = {b.lo - e, b.hi + e};
            break;
        }
        case ShapeType::plane: {
            const float inf = std::numeric_limits<float>::infinity();
            return {Vec3{-inf}, Vec3{inf}};
        }
        case ShapeType::triangle:
            for (const Vec3& p : s.vertices) b.expand(s.transform.point(p));
            break;
        case ShapeType::mesh:
            if (!s.mesh || s.mesh->bounds.empty()) return Bounds3{};  // no triangles: empty
            b = s.mesh->bounds;
            break;
    }
    return pad(b);
}

}  // namespace luz
