// Cone: radius 1 − (1 − k)·z around +z, z ∈ [0, 1] in object space (k = apex_radius / radius:
// 0 is a full cone with its apex at z = 1, k > 0 a frustum with a disc of radius k at z = 1),
// placed from `base` along `axis` by `radius` and `height`; `cap` closes the base (part_cap0)
// and a frustum's top disc (part_cap1).
#pragma once

#include <algorithm>
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
        s.apex = o.apex_radius / o.radius;
    }

    static Bounds3 bounds(const Shape& s) {
        // The base rim and the apex (a frustum: the top rim).
        const Affine& M = s.transform.world_from_object;
        const Vec3 U = column(M, 0), V = column(M, 1), W = column(M, 2);
        Bounds3 b = ellipse_bounds(origin(M), U, V);
        if (s.apex > 0)
            b.expand(ellipse_bounds(origin(M) + W, U * s.apex, V * s.apex));
        else
            b.expand(origin(M) + W);
        return pad(b);
    }

    /// Bounds of the part z0 ≤ z ≤ z1 (0 ≤ z0 < z1 ≤ 1): the rims there, of radius 1 − m·z.
    static Bounds3 bounds(const Shape& s, float z0, float z1) {
        const Affine& M = s.transform.world_from_object;
        const Vec3 U = column(M, 0), V = column(M, 1), W = column(M, 2);
        const float m = 1.0f - s.apex;
        Bounds3 b;
        for (const float z : {z0, z1}) {
            const float k = std::max(0.0f, 1.0f - m * z);  // a cone's apex: 0, a point
            b.expand(ellipse_bounds(origin(M) + W * z, U * k, V * k));
        }
        return pad(b);
    }

    /// x² + y² = (1 − m·z)², z ∈ [0, 1], with m = 1 − k the slope; the caps at z = 0 and (a
    /// frustum) z = 1.
    static bool hit_object(const Shape& s, const Ray& ro, Nearest& n) {
        const D3 o = to_d3(ro.origin), d = to_d3(ro.direction);
        const double m = 1.0 - double(s.apex);
        // with w = 1 − m·z: x² + y² − w² = 0, w(t) = (1 − m·oz) − t·m·dz
        const double w0 = 1.0 - m * o.z, wd = m * d.z;
        const double a = d.x * d.x + d.y * d.y - wd * wd;
        const double b = o.x * d.x + o.y * d.y + w0 * wd;
        const double c = o.x * o.x + o.y * o.y - w0 * w0;
        // Outside (c > 0), moving outwards (b > 0) and a ≥ 0, as most rays leaving the side
        // outwards: both roots are negative (q < 0: c/q < 0, q/a < 0 or −∞), and
        // Nearest::offer() would reject them for t_min ≥ 0, so they are not computed.
        const bool behind = c > 0 && b > 0 && a >= 0 && n.t_min >= 0;
        const double disc = behind ? -1.0 : b * b - a * c;
        if (disc >= 0) {
            double r[2];
            quadratic_roots(a, b, c, disc, r[0], r[1]);  // a = 0 (parallel to a generator): c/q
            for (double t : r) {
                // z ≤ 1 drops the mirrored nappe beyond the apex (at z = 1/m ≥ 1)
                const double z = o.z + t * d.z;
                if (z >= 0 && z <= 1) n.offer(t, part_side);
            }
        }
        if (s.caps) hit_caps(o, d, s.apex > 0, n, double(s.apex) * s.apex);
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
        const float m = 1.0f - s.apex;
        return surface_from_object_normal(s, r, hit, [m](const Vec3& p, int part) {
            if (part != part_side) return Vec3{0, 0, part == part_cap1 ? 1.0f : -1.0f};
            // ∇(x² + y² − (1 − m·z)²) ∝ (x, y, m·(1 − m·z)) = (x, y, m·r) on the surface; using
            // r = √(x² + y²) keeps it exact near the apex, where (0, 0, 1) is the choice
            const float rr = std::sqrt(p.x * p.x + p.y * p.y);
            return rr > 0 ? Vec3{p.x, p.y, m * rr} : Vec3{0, 0, 1};
        });
    }

    /// A full cone's side as one triangle per segment from the base rim to the apex. The normal
    /// at the apex is undefined, so each segment has its own apex vertex (same position) with
    /// the normal of the segment's mid-angle. A frustum's side is one quad per segment.
    static void tessellate(const Shape& s, int level, TriangleMesh& out) {
        if (s.apex > 0) return tessellate_frustum(s, level, out);
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

    /// The frustum: vertex (j, 0) on the base rim and (j, 1) on the top rim (radius k), both with
    /// the side normal ∝ ∇(√(x²+y²) + m·z − 1) = (cosφ, sinφ, m); caps at both ends.
    static void tessellate_frustum(const Shape& s, int level, TriangleMesh& out) {
        Emitter e(s.transform, out);
        const int n = level;
        const Circle circle(n);
        const float k = s.apex, m = 1.0f - k;
        e.reserve(2 * size_t(n) + (s.caps ? 2 * size_t(n + 1) : 0),
                  2 * size_t(n) + (s.caps ? 2 * n : 0));
        emit_side(e, circle, k, m);
        if (s.caps) {
            emit_cap(e, circle, 0.0f, false);
            emit_cap(e, circle, 1.0f, true, k);
        }
    }

    /// π(r + r′)·slant + πr² + πr′² (the caps), r′ = k·r the apex radius, slant = √((r − r′)² +
    /// h²).
    static double area(const Shape& s) {
        const Affine& M = s.transform.world_from_object;
        const double r = 0.5 * (axis_length(M, 0) + axis_length(M, 1)), h = axis_length(M, 2);
        const double r2 = r * s.apex;
        return pi * (r + r2) * std::sqrt((r - r2) * (r - r2) + h * h) +
               (s.caps ? pi * (r * r + r2 * r2) : 0.0);
    }
};

}  // namespace luz::shapes
