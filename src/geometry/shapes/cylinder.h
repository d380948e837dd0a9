// Cylinder: radius 1 around +z, z ∈ [0, 1] in object space, placed from `base` along `axis` by
// `radius` and `height`; `caps` closes z = 0 and z = 1 (Hit::part part_cap0, part_cap1). An open
// cylinder whose transform keeps it round is hit in world form (base, axis, radius, height:
// ray_cylinder.h), falling back to object space in double where float cannot be trusted.
#pragma once

#include <cstdint>

#include "geometry/ray_cylinder.h"
#include "geometry/shapes/caps.h"
#include "geometry/shapes/emitter.h"
#include "geometry/shapes/object_space.h"
#include "geometry/shapes/placement.h"

namespace luz::shapes {

struct cylinder {
    static constexpr bool bounded = true;

    /// Placement, and the world form (centre: the base; normal: the unit axis; radius; offset:
    /// the height) of an open cylinder whose transform keeps it round (is_round_frame()).
    static void place(const ObjectDesc& o, Shape& s) {
        set_transform(s, o, frame_along(o.axis, o.radius, o.radius, o.height, o.base));
        s.caps = o.caps;
        const Affine& M = s.transform.world_from_object;
        if (!s.caps && is_round_frame(M)) {
            const Vec3 W = column(M, 2);
            s.world_form = true;
            s.centre = origin(M);
            s.normal = normalize(W);
            s.radius = length(column(M, 0));
            s.offset = length(W);
        }
    }

    static Bounds3 bounds(const Shape& s) {
        // The two rims (ellipses in world space) bound the whole cylinder.
        const Affine& M = s.transform.world_from_object;
        const Vec3 U = column(M, 0), V = column(M, 1), W = column(M, 2);
        Bounds3 b = ellipse_bounds(origin(M), U, V);
        b.expand(ellipse_bounds(origin(M) + W, U, V));
        return pad(b);
    }

    /// Bounds of the part z0 ≤ z ≤ z1 (0 ≤ z0 < z1 ≤ 1): a piece of it in the BVH (build_bvh()).
    static Bounds3 bounds(const Shape& s, float z0, float z1) {
        const Affine& M = s.transform.world_from_object;
        const Vec3 U = column(M, 0), V = column(M, 1), W = column(M, 2);
        Bounds3 b = ellipse_bounds(origin(M) + W * z0, U, V);
        b.expand(ellipse_bounds(origin(M) + W * z1, U, V));
        return pad(b);
    }

    static bool hit_object(const Shape& s, const Ray& ro, Nearest& n) {
        const D3 o = to_d3(ro.origin), d = to_d3(ro.direction);
        const double a = d.x * d.x + d.y * d.y;
        if (a > 0) {
            const double b = o.x * d.x + o.y * d.y, c = o.x * o.x + o.y * o.y - 1.0;
            // Outside the side (c > 0) and moving away from the axis (b > 0), as every ray
            // leaving the side outwards: both roots are negative (q < 0: c/q, q/a < 0), and
            // Nearest::offer() would reject them for t_min ≥ 0, so they are not computed.
            const bool behind = c > 0 && b > 0 && n.t_min >= 0;
            // as for the sphere, in the xy projection: disc = a·(1 − |o⊥ − (b/a)·d⊥|²)
            const double lx = o.x - b / a * d.x, ly = o.y - b / a * d.y;
            const double disc = behind ? -1.0 : a * (1.0 - (lx * lx + ly * ly));
            if (disc >= 0) {
                double r[2];
                quadratic_roots(a, b, c, disc, r[0], r[1]);
                for (double t : r) {
                    const double z = o.z + t * d.z;
                    if (z >= 0 && z <= 1) n.offer(t, part_side);
                }
            }
        }
        if (s.caps) hit_caps(o, d, true, n);
        return n.found;
    }

    /// The world form's roots (world_cylinder_roots(); `slow`: test in object space).
    static CylinderRoots world_roots(const Shape& s, const Ray& r, float& t0, float& t1) {
        return world_cylinder_roots(s.centre, s.normal, s.radius * s.radius, s.offset, r, t0, t1);
    }

    static bool intersect_object(const Shape& s, const Ray& r, float t_min, float t_max, Hit& hit) {
        return intersect_in_object_space(s, r, t_min, t_max, hit, [&](const Ray& ro, Nearest& n) {
            return hit_object(s, ro, n);
        });
    }

    static bool intersect(const Shape& s, const Ray& r, float t_min, float t_max, Hit& hit) {
        float t0 = 0, t1 = 0;
        const CylinderRoots met = s.world_form ? world_roots(s, r, t0, t1) : CylinderRoots::slow;
        if (met == CylinderRoots::slow) return intersect_object(s, r, t_min, t_max, hit);
        return met == CylinderRoots::met && hit_at_roots(t0, t1, t_min, t_max, hit);
    }

    static uint32_t count_crossings(const Shape& s, const Ray& r, float t_min, float t_max,
                                    bool first_only, uint64_t& tests) {
        float t0 = 0, t1 = 0;
        const CylinderRoots met = s.world_form ? world_roots(s, r, t0, t1) : CylinderRoots::slow;
        if (met != CylinderRoots::slow)
            return crossings_at_roots(met == CylinderRoots::met, t0, t1, t_min, t_max, first_only,
                                      tests);
        return count_by_repeated_hits(
            t_min, t_max, first_only, tests,
            [&](float lo, float hi, Hit& h) { return intersect_object(s, r, lo, hi, h); });
    }

    static SurfacePoint surface_at(const Shape& s, const Ray& r, const Hit& hit) {
        if (s.world_form) {  // N: the hit point's part across the axis (open: the side only)
            SurfacePoint sp;
            sp.P = r.at(hit.t);
            const Vec3 e = sp.P - s.centre;
            sp.N = unit_or(e - s.normal * dot(e, s.normal), {1, 0, 0});
            sp.Ng = sp.N;
            return sp;
        }
        return surface_from_object_normal(s, r, hit, [](const Vec3& p, int part) {
            if (part == part_side) return unit_or({p.x, p.y, 0}, {1, 0, 0});
            return Vec3{0, 0, part == part_cap0 ? -1.0f : 1.0f};
        });
    }

    /// One segment along the side (normals are constant along it), optional caps.
    static void tessellate(const Shape& s, int level, TriangleMesh& out) {
        Emitter e(s.transform, out);
        const int n = level;
        const Circle circle(n);
        e.reserve(2 * size_t(n) + (s.caps ? 2 * size_t(n + 1) : 0),
                  2 * size_t(n) + (s.caps ? 2 * n : 0));
        emit_side(e, circle);
        if (s.caps) {
            emit_cap(e, circle, 0.0f, false);
            emit_cap(e, circle, 1.0f, true);
        }
    }

    /// 2πrh + 2πr² (the caps).
    static double area(const Shape& s) {
        const Affine& M = s.transform.world_from_object;
        const double r = 0.5 * (axis_length(M, 0) + axis_length(M, 1)), h = axis_length(M, 2);
        return 2.0 * pi * r * h + (s.caps ? 2.0 * pi * r * r : 0.0);
    }
};

}  // namespace luz::shapes
