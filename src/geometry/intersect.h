// Ray–shape intersection for the ray tracer (SPEC §1.1): the nearest hit of a ray with one
// shape in its canonical object space (shape.h), and the surface data at that hit.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "geometry/shape.h"
#include "math/ray.h"
#include "math/vec3.h"

namespace luz {

/// Which surface of a shape a hit lies on (Hit::part).
enum HitPart : int {
    part_side = 0,  ///< sphere, torus, plane, triangle, the side of a cylinder or cone
    part_cap0 = 1,  ///< cylinder and cone: the disc at z = 0
    part_cap1 = 2,  ///< cylinder: the disc at z = 1
    // box: part = 2·axis + (1 on the hi face, 0 on the lo face), i.e. 0 … 5
};

/// A ray–shape hit: cheap, plain, filled for every candidate; shading data comes later from
/// surface_at() for the nearest hit only.
struct Hit {
    float t = 0;     ///< ray parameter: world point = r.origin + t·r.direction
    int shape = -1;  ///< index of the shape in its scene; intersect() leaves it to the caller
    /// Triangles: the barycentrics of vertices 1 and 2 (P = (1−u−v)·v0 + u·v1 + v·v2);
    /// 0 for the other shapes (nothing needs their surface parameters yet).
    float u = 0, v = 0;
    int part = part_side;  ///< HitPart, the box face, or a mesh's triangle index
};

namespace detail {
bool world_sphere_roots_double(const Vec3& centre, float radius, const Ray& r, float& t0,
                               float& t1);
bool intersect_object_space(const Shape& s, const Ray& r, float t_min, float t_max, Hit& hit);
uint32_t count_crossings_object_space(const Shape& s, const Ray& r, float t_min, float t_max,
                                      bool first_only, uint64_t& tests);
}  // namespace detail

/// The roots t0 ≤ t1 of world ray r with the sphere of `centre` and `radius` (a sphere in world
/// form, Shape::world_form), false if it misses. Solved in float (the roots c/q and q/a of a·t² +
/// 2b·t + c with q = −(b ± √disc), disc without cancellation as Haines et al., Ray Tracing Gems ch.
/// 7), or in double where float cannot be trusted: c = |o|² − ρ² near 0 (an origin on the surface,
/// as spawned secondary and shadow rays have), whose sign decides whether the near root lies ahead.
inline bool world_sphere_roots(const Vec3& centre, float radius, const Ray& r, float& t0,
                               float& t1) {
    const Vec3 o = r.origin - centre, d = r.direction;
    const float rr = radius * radius;
    const float a = dot(d, d), b = dot(o, d), oo = dot(o, o), c = oo - rr;
    // |error of c| ≤ ~3 ulp of max(|o|², ρ²); beyond 2^-17 of it, c's sign is sure and the
    // near root's error stays at the float rounding of the ray itself.
    if (std::fabs(c) < 0x1p-17f * std::max(oo, rr) || !(a > 0)) {
        return detail::world_sphere_roots_double(centre, radius, r, t0, t1);
    }
    const float inv_a = 1.0f / a;
    const Vec3 l = o - d * (b * inv_a);
    const float disc = a * (rr - dot(l, l));
    if (disc < 0) return false;
    const float q = -(b + std::copysign(std::sqrt(disc), b));
    const float f0 = c / q, f1 = q * inv_a;
    t0 = std::min(f0, f1);
    t1 = std::max(f0, f1);
    return true;
}

/// The root of world ray r with plane s in world form: n·(o + t·d) = offset (±inf or NaN if
/// the ray is parallel). n·o in double: no cancellation for origins on the plane.
inline float world_plane_root(const Shape& s, const Ray& r) {
    const double n_o = double(s.normal.x) * r.origin.x + double(s.normal.y) * r.origin.y +
                       double(s.normal.z) * r.origin.z;
    return static_cast<float>(double(s.offset) - n_o) / dot(s.normal, r.direction);
}

/// The nearest of the roots t0 ≤ t1 (of a sphere or a plane in world form) in the open interval
/// (t_min, t_max), in t; false if neither lies there (NaN roots never do).
inline bool nearest_root(float t0, float t1, float t_min, float t_max, float& t) {
    t = t0 > t_min ? t0 : t1;
    return t > t_min && t < t_max;
}

/// How many of the roots t0, t1 lie in the open interval (t_min, t_max) (NaN roots never do).
inline uint32_t roots_within(float t0, float t1, float t_min, float t_max) {
    return (t0 > t_min && t0 < t_max ? 1 : 0) + (t1 > t_min && t1 < t_max ? 1 : 0);
}

/// Nearest hit of world ray r with shape s in the open interval (t_min, t_max). Spheres under a
/// similarity and planes are hit in world space (Shape::world_form); the other shapes in
/// object space (transform.to_object, direction not normalised), so t is the same in both
/// spaces. Valid for rays starting inside the shape (refraction). A mesh tests every
/// triangle (intersect_mesh); the scene queries use the BVH instead.
inline bool intersect(const Shape& s, const Ray& r, float t_min, float t_max, Hit& hit) {
    if (!s.world_form) return detail::intersect_object_space(s, r, t_min, t_max, hit);
    float t0, t1;
    if (s.type == ShapeType::sphere) {
        if (!world_sphere_roots(s.centre, s.radius, r, t0, t1)) return false;
    } else {
        t0 = t1 = world_plane_root(s, r);
    }
    float t;
    if (!nearest_root(t0, t1, t_min, t_max, t)) return false;
    hit.t = t;
    hit.u = hit.v = 0;
    hit.part = part_side;
    return true;
}

/// How many times r crosses s in (t_min, t_max) (a closed shape counts twice), or at most 1
/// with `first_only` (enough to know an opaque shape blocks); `tests` counts the ray–shape
/// tests made. Planes and spheres in world form count their roots directly; other shapes
/// repeat intersect() past each crossing (up to 64).
inline uint32_t count_crossings(const Shape& s, const Ray& r, float t_min, float t_max,
                                bool first_only, uint64_t& tests) {
    if (!s.world_form) {
        return detail::count_crossings_object_space(s, r, t_min, t_max, first_only, tests);
    }
    ++tests;
    float t0, t1;
    if (s.type == ShapeType::sphere) {
        if (!world_sphere_roots(s.centre, s.radius, r, t0, t1)) return 0;
    } else {
        t0 = world_plane_root(s, r);
        t1 = std::numeric_limits<float>::quiet_NaN();  // one root only
    }
    const uint32_t n = roots_within(t0, t1, t_min, t_max);
    return first_only && n > 1 ? 1 : n;
}

/// Surface data at a hit: world position, unit outward shading normal (object normal by the
/// inverse transpose, normalised), unit outward geometric normal. For triangles both are the
/// winding normal (v1 − v0) × (v2 − v0); two-sided shading flips them later (SPEC §1.3). For
/// mesh triangles (Hit::part = triangle), N is the interpolated vertex normal of a smooth mesh
/// and Ng the face normal.
struct SurfacePoint {
    Vec3 P, N, Ng;
};
SurfacePoint surface_at(const Shape& s, const Ray& r, const Hit& hit);

/// The material at a hit: the shape's, or for a mesh that of the triangle hit.
inline int material_at(const Shape& s, const Hit& hit) {
    return s.mesh ? s.mesh->materials[static_cast<size_t>(hit.part)] : s.material;
}

/// A ray prepared once for the watertight ray–triangle test of Woop, Benthin and Wald (JCGT
/// 2013): the dominant axis kz of the direction, and the shear that maps the ray onto +z.
struct WatertightRay {
    Vec3 origin;
    int kx = 0, ky = 1, kz = 2;
    float Sx = 0, Sy = 0, Sz = 1;
};
/// Prepares ray r (any non-zero direction) for intersect_triangle().
WatertightRay prepare_watertight(const Ray& r);

/// Watertight ray–triangle test: hit in (t_min, t_max) at t with barycentrics b1, b2 of p1,
/// p2. Rays through an edge or vertex shared by several triangles (same float vertices) hit
/// at least one of them. Both sides count.
bool intersect_triangle(const WatertightRay& r, const Vec3& p0, const Vec3& p1, const Vec3& p2,
                        float t_min, float t_max, float& t, float& b1, float& b2);

/// The nearest hit among all triangles of `mesh` (in index order; ties keep the lowest index):
/// hit.part = the triangle, hit.u, hit.v its barycentrics. hit.shape is left to the caller.
bool intersect_mesh(const Mesh& mesh, const WatertightRay& w, float t_min, float t_max, Hit& hit);

}  // namespace luz
