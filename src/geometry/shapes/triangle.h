// Triangle: its three `vertices` as the keys give them, in object space (the user transform
// only); two-sided, hit by the watertight test (ray_triangle.h), hit.u, hit.v its barycentrics.
#pragma once

#include <cstdint>

#include "geometry/ray_triangle.h"
#include "geometry/shapes/emitter.h"
#include "geometry/shapes/object_space.h"
#include "geometry/shapes/placement.h"

namespace luz::shapes {

struct triangle {
    static constexpr bool bounded = true;

    static void place(const ObjectDesc& o, Shape& s) {
        for (int k = 0; k < 3; ++k) s.vertices[k] = o.vertices[k];
        set_transform(s, o, Affine{});
    }

    static Bounds3 bounds(const Shape& s) {
        Bounds3 b;
        for (const Vec3& p : s.vertices) b.expand(s.transform.point(p));
        return pad(b);
    }

    /// Out of line (object_space.h: intersect_in_object_space).
    [[gnu::noinline]] static bool intersect(const Shape& s, const Ray& r, float t_min, float t_max,
                                            Hit& hit) {
        const WatertightRay w = prepare_watertight(s.transform.to_object(r));
        float t, b1, b2;
        if (!intersect_triangle(w, s.vertices[0], s.vertices[1], s.vertices[2], t_min, t_max, t, b1,
                                b2))
            return false;
        hit.t = t;
        hit.u = b1;
        hit.v = b2;
        hit.part = part_side;
        return true;
    }

    static uint32_t count_crossings(const Shape& s, const Ray& r, float t_min, float t_max,
                                    bool first_only, uint64_t& tests) {
        return count_by_repeated_hits(
            t_min, t_max, first_only, tests,
            [&](float t0, float t1, Hit& h) { return intersect(s, r, t0, t1, h); });
    }

    /// Both normals are the winding normal (v1 − v0) × (v2 − v0).
    static SurfacePoint surface_at(const Shape& s, const Ray& r, const Hit& hit) {
        const Vec3 n = cross(s.vertices[1] - s.vertices[0], s.vertices[2] - s.vertices[0]);
        return surface_from_object_normal(s, r, hit, [&](const Vec3&, int) { return n; });
    }

    static void tessellate(const Shape& s, int, TriangleMesh& out) {
        Emitter e(s.transform, out);
        const Vec3 n = cross(s.vertices[1] - s.vertices[0], s.vertices[2] - s.vertices[0]);
        const uint32_t a = e.vertex(s.vertices[0], n), b = e.vertex(s.vertices[1], n),
                       c = e.vertex(s.vertices[2], n);
        e.triangle(a, b, c);
    }

    static double area(const Shape& s) {
        const Vec3 a = s.transform.point(s.vertices[0]), b = s.transform.point(s.vertices[1]),
                   c = s.transform.point(s.vertices[2]);
        return 0.5 * double(length(cross(b - a, c - a)));
    }
};

}  // namespace luz::shapes
