// What a ray query reports: a cheap Hit for every candidate, the SurfacePoint of the nearest
// one, and the rules for picking a root within an interval.
#pragma once

#include <cstdint>

#include "geometry/shape.h"
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

/// Surface data at a hit: world position, unit outward shading normal (object normal by the
/// inverse transpose, normalised), unit outward geometric normal. For triangles both are the
/// winding normal (v1 − v0) × (v2 − v0); two-sided shading flips them later
/// (docs/SCENES.md#geometry). For mesh triangles (Hit::part = triangle), N is the interpolated
/// vertex normal of a smooth mesh and Ng the face normal.
struct SurfacePoint {
    Vec3 P, N, Ng;
};

/// The material at a hit: the shape's, or for a mesh that of the triangle hit.
inline int material_at(const Shape& s, const Hit& hit) {
    return s.mesh ? s.mesh->materials[static_cast<size_t>(hit.part)] : s.material;
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

}  // namespace luz
