// Every shape in one place: includes each shape's file (shapes/<name>.h) and dispatches on
// Shape::type by the one switch generated from LUZ_SHAPES (scene/shape_desc.h). A new shape is
// its entry there, its file shapes/<name>.h, and its include line here.
#pragma once

#include <algorithm>
#include <cstdint>

#include "geometry/hit.h"
#include "geometry/shape.h"
#include "math/ray.h"
#include "scene/shape_desc.h"

// One file per shape: each is a struct shapes::<name> with the same static members (see
// shapes/sphere.h): bounded, place, bounds, intersect, count_crossings, surface_at, tessellate,
// area.
#include "geometry/shapes/box.h"
#include "geometry/shapes/cone.h"
#include "geometry/shapes/cylinder.h"
#include "geometry/shapes/mesh.h"
#include "geometry/shapes/plane.h"
#include "geometry/shapes/sphere.h"
#include "geometry/shapes/torus.h"
#include "geometry/shapes/triangle.h"

namespace luz {

/// Calls f(shapes::<name>{}) for the shape type t and returns its result: the only switch on
/// the shape type. Always inlined (else GCC may leave it out of line in the queries' loops).
template <class F>
[[gnu::always_inline]] inline decltype(auto) visit_shape(ShapeType t, F&& f) {
    switch (t) {
#define LUZ_SHAPE_CASE(name) \
    case ShapeType::name:    \
        return f(shapes::name{});
        LUZ_SHAPES(LUZ_SHAPE_CASE)
#undef LUZ_SHAPE_CASE
    }
    __builtin_unreachable();  // a ShapeType outside the list
}

// A lambda inlined into its caller: GCC reads the standard attribute there, clang the GNU one.
#if defined(__clang__)
#define LUZ_INLINE_LAMBDA __attribute__((always_inline))
#else
#define LUZ_INLINE_LAMBDA [[gnu::always_inline]]
#endif

/// Nearest hit of world ray r with shape s in the open interval (t_min, t_max). Spheres under a
/// similarity, open round cylinders and planes are hit in world space (Shape::world_form); the
/// other shapes in
/// object space (transform.to_object, direction not normalised), so t is the same in both
/// spaces. Valid for rays starting inside the shape (refraction). A mesh tests every
/// triangle (intersect_mesh); the scene queries use the BVH instead.
[[gnu::always_inline]] inline bool intersect(const Shape& s, const Ray& r, float t_min, float t_max,
                                             Hit& hit) {
    return visit_shape(s.type, [&](auto shape) LUZ_INLINE_LAMBDA {
        return decltype(shape)::intersect(s, r, t_min, t_max, hit);
    });
}

/// How many times r crosses s in (t_min, t_max) (a closed shape counts twice), or at most 1
/// with `first_only` (enough to know an opaque shape blocks); `tests` counts the ray–shape
/// tests made. Planes, spheres and cylinders in world form count their roots directly; others
/// repeat intersect() past each crossing (up to 64).
[[gnu::always_inline]] inline uint32_t count_crossings(const Shape& s, const Ray& r, float t_min,
                                                       float t_max, bool first_only,
                                                       uint64_t& tests) {
    return visit_shape(s.type, [&](auto shape) LUZ_INLINE_LAMBDA {
        return decltype(shape)::count_crossings(s, r, t_min, t_max, first_only, tests);
    });
}

/// Surface data at a hit of r with s (hit.h: SurfacePoint).
SurfacePoint surface_at(const Shape& s, const Ray& r, const Hit& hit);

}  // namespace luz
