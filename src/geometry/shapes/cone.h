// Cone: radius 1 − z around +z, z ∈ [0, 1] in object space (apex at z = 1), placed from `base`
// along `axis` by `radius` and `height`; `caps` (the `cap` key) closes the base (part_cap0).
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "geometry/shapes/caps.h"
#include "geometry/shapes/emitter.h"
#include "geometry/shapes/object_space.h"
#include "geometry/shapes/placement.h"

namespace luz::shapes {

struct cone {
    static constexpr bool bounded = true;

    static void place(const ObjectDesc& o, Shape& s) {
        set_transform(s, o, frame_along(o.axis, o.radius, o.radius, o.height, o.base));
        s.caps = o.caps;
    }

    static Bounds3 bounds(const Shape& s) {
        // The base rim and the apex.
        const Affine& M = s.transform.world_from_object;
        const Vec3 U = column(M, 0), V = column(M, 1), W = column(M, 2);
        Bounds3 b = ellipse_bounds(origin(M), U, V);
        b.expand(origin(M) + W);
        return pad(b);
    }

    /// x² + y² = (1 − z)², z ∈ [0, 1]; the cap at z = 0.
    static bool hit_object(const Shape& s, const Ray& ro, Nearest& n) {
        const D3 o = to_d3(ro.origin), d = to_d3(ro.direction);
        // with w = 1 − z: x² + y² − w² = 0, w(t) = (1 − oz) − t·dz
        const double w0 = 1.0 - o.z;
        const double a = d.x * d.x + d.y * d.y - d.z * d.z;
        const double b = o.x * d.x + o.y * d.y + w0 * d.z;
        const double c = o.x * o.x + o.y * o.y - w0 * w0;
        const double disc = b * b - a * c;
        if (disc >= 0) {
            double r[2];
            quadratic_roots(a, b, c, disc, r[0], r[1]);  // a = 0 (parallel to a generator): c/q
            for (double t : r) {
                const double z = o.z + t * d.z;  // z ≤ 1 drops the mirrored nappe above the apex
                if (z >= 0 && z <= 1) n.offer(t, part_side);
            }
        }
        if (s.caps) hit_caps(o, d, false, n);
        return n.found;
    }

    static bool intersect(const Shape& s, const Ray& r, float t_min, float t_max, Hit& hit) {
        return intersect_in_object_space(s, r, t_min, t_max, hit, [&](const Ray& ro, Nearest& n) {
            return hit_object(s, ro, n);
        });
    }

    static uint32_t count_crossings(const Shape& s, const Ray& r, float t_min, float t_max,
                                    bool first_only, uint64_t& tests) {
        return count_by_repeated_hits(
            t_min, t_max, first_only, tests,
            [&](float t0, float t1, Hit& h) { return intersect(s, r, t0, t1, h); });
    }

    static SurfacePoint surface_at(const Shape& s, const Ray& r, const Hit& hit) {
        return surface_from_object_normal(s, r, hit, [](const Vec3& p, int part) {
            if (part != part_side) return Vec3{0, 0, -1};
            // ∇(x² + y² − (1 − z)²) ∝ (x, y, 1 − z) = (x, y, r) on the surface; using
            // r = √(x² + y²) keeps it exact near the apex, where (0, 0, 1) is the choice
            const float rr = std::sqrt(p.x * p.x + p.y * p.y);
            return rr > 0 ? Vec3{p.x, p.y, rr} : Vec3{0, 0, 1};
        });
    }

    /// The side as one triangle per segment from the base rim to the apex. The normal at the
    /// apex is undefined, so each segment has its own apex vertex (same position) with the
    /// normal of the segment's mid-angle.
    static void tessellate(const Shape& s, int level, TriangleMesh& out) {
        Emitter e(s.transform, out);
        const int n = level;
        const Circle circle(n);
        e.reserve(2 * size_t(n) + (s.caps ? size_t(n + 1) : 0), size_t(n) + (s.caps ? n : 0));
        // Side normal ∝ ∇(√(x²+y²) + z − 1) = (cosφ, sinφ, 1).
        std::vector<uint32_t> rim(n);
        for (int j = 0; j < n; ++j)
            rim[j] = e.vertex({circle.c[j], circle.s[j], 0}, {circle.c[j], circle.s[j], 1});
        for (int j = 0; j < n; ++j) {
            const double mid = 2.0 * pi * (j + 0.5) / n;
            const uint32_t apex = e.vertex({0, 0, 1}, {static_cast<float>(std::cos(mid)),
                                                       static_cast<float>(std::sin(mid)), 1});
            // φ̂ × (ẑ − r̂) = r̂ + ẑ: outward.
            e.triangle(rim[j], rim[(j + 1) % n], apex);
        }
        if (s.caps) emit_cap(e, circle, 0.0f, false);
    }

    /// πr·slant + πr² (the base).
    static double area(const Shape& s) {
        const Affine& M = s.transform.world_from_object;
        const double r = 0.5 * (axis_length(M, 0) + axis_length(M, 1)), h = axis_length(M, 2);
        return pi * r * std::sqrt(r * r + h * h) + (s.caps ? pi * r * r : 0.0);
    }
};

}  // namespace luz::shapes
