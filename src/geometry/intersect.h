// Ray–shape intersection for the ray tracer (SPEC §1.1): the nearest hit of a ray with one
// shape in its canonical object space (shape.h), and the surface data at that hit.
#pragma once

#include <cstdint>

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

/// Nearest hit of world ray r with shape s in the open interval (t_min, t_max). The ray is
/// moved into object space (transform.to_object, direction not normalised), so t is the same
/// in both spaces. Valid for rays starting inside the shape (refraction). A mesh tests every
/// triangle (intersect_mesh); the scene queries use the BVH instead.
bool intersect(const Shape& s, const Ray& r, float t_min, float t_max, Hit& hit);

/// How many times r crosses s in (t_min, t_max) (a closed shape counts twice), or at most 1
/// with `first_only` (enough to know an opaque shape blocks); `tests` counts the ray–shape
/// tests made. Planes and spheres in world form count their roots directly; other shapes
/// repeat intersect() past each crossing (up to 64).
uint32_t count_crossings(const Shape& s, const Ray& r, float t_min, float t_max, bool first_only,
                         uint64_t& tests);

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
