// Plane: z = 0 in object space with outward normal +z, placed at `point` facing `normal`;
// unbounded. Hit in world form (unit normal n, n·p = offset) in float with n·o in double.
#pragma once

#include <cstdint>
#include <limits>

#include "geometry/shapes/object_space.h"
#include "geometry/shapes/placement.h"

namespace luz::shapes {

struct plane {
    static constexpr bool bounded = false;

    /// Placement, and the world form: the object normal +z by the inverse transpose, as
    /// surface_at() gives it.
    static void place(const ObjectDesc& o, Shape& s) {
        set_transform(s, o, frame_along(o.normal, 1.0f, 1.0f, 1.0f, o.point));
        const Vec3 n = s.transform.normal({0, 0, 1});
        const float l = length(n);
        if (l > 0 && std::isfinite(l)) {
            s.world_form = true;
            s.normal = n / l;
            s.offset = dot(s.normal, origin(s.transform.world_from_object));
        }
    }

    /// Infinite: planes are tested apart from the BVH.
    static Bounds3 bounds(const Shape&) {
        const float inf = std::numeric_limits<float>::infinity();
        return {Vec3{-inf}, Vec3{inf}};
    }

    /// The root of world ray r with the plane in world form: n·(o + t·d) = offset (±inf or NaN
    /// if the ray is parallel). n·o in double: no cancellation for origins on the plane.
    static float world_root(const Shape& s, const Ray& r) {
        const double n_o = double(s.normal.x) * r.origin.x + double(s.normal.y) * r.origin.y +
                           double(s.normal.z) * r.origin.z;
        return static_cast<float>(double(s.offset) - n_o) / dot(s.normal, r.direction);
    }

    static bool hit_object(const Ray& ro, Nearest& n) {
        if (ro.direction.z == 0.0f) return false;
        return n.offer(-double(ro.origin.z) / ro.direction.z, part_side);
    }

    static bool intersect(const Shape& s, const Ray& r, float t_min, float t_max, Hit& hit) {
        if (!s.world_form) return intersect_in_object_space(s, r, t_min, t_max, hit, hit_object);
        const float t = world_root(s, r);
        return hit_at_roots(t, t, t_min, t_max, hit);
    }

    static uint32_t count_crossings(const Shape& s, const Ray& r, float t_min, float t_max,
                                    bool first_only, uint64_t& tests) {
        if (!s.world_form) {
            return count_by_repeated_hits(
                t_min, t_max, first_only, tests, [&](float t0, float t1, Hit& h) {
                    return intersect_in_object_space(s, r, t0, t1, h, hit_object);
                });
        }
        const float nan = std::numeric_limits<float>::quiet_NaN();  // one root only
        return crossings_at_roots(true, world_root(s, r), nan, t_min, t_max, first_only, tests);
    }

    static SurfacePoint surface_at(const Shape& s, const Ray& r, const Hit& hit) {
        if (s.world_form) return {r.at(hit.t), s.normal, s.normal};
        return surface_from_object_normal(s, r, hit, [](const Vec3&, int) {
            return Vec3{0, 0, 1};
        });
    }

    /// Nothing: the rasterizer draws planes as quads clipped to the view.
    static void tessellate(const Shape&, int, TriangleMesh&) {}

    static double area(const Shape&) { return std::numeric_limits<double>::infinity(); }
};

}  // namespace luz::shapes
