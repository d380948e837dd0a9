// Box: the axis-aligned box [lo, hi] of its `min` and `max` keys, in object space (the user
// transform only); hit by slabs. Hit::part is the face: 2·axis + (1 on the hi face).
#pragma once

#include <cstdint>
#include <limits>
#include <utility>

#include "geometry/shapes/emitter.h"
#include "geometry/shapes/object_space.h"
#include "geometry/shapes/placement.h"

namespace luz::shapes {

struct box {
    static constexpr bool bounded = true;

    static void place(const ObjectDesc& o, Shape& s) {
        s.lo = min(o.min, o.max);
        s.hi = max(o.min, o.max);
        set_transform(s, o, Affine{});
    }

    static Bounds3 bounds(const Shape& s) { return pad(s.transform.bounds(Bounds3{s.lo, s.hi})); }

    static bool hit_object(const Shape& s, const Ray& ro, Nearest& n) {
        const float inf = std::numeric_limits<float>::infinity();
        float t_near = -inf, t_far = inf;
        int f_near = -1, f_far = -1;
        for (int k = 0; k < 3; ++k) {
            const float o = ro.origin[k], d = ro.direction[k];
            if (d == 0.0f) {
                // parallel to the slab: inside it or a miss (no 0·inf NaN)
                if (o < s.lo[k] || o > s.hi[k]) return false;
                continue;
            }
            const float inv = 1.0f / d;
            float ta = (s.lo[k] - o) * inv, tb = (s.hi[k] - o) * inv;
            int fa = 2 * k, fb = 2 * k + 1;
            if (ta > tb) {
                std::swap(ta, tb);
                std::swap(fa, fb);
            }
            if (ta > t_near) t_near = ta, f_near = fa;
            if (tb < t_far) t_far = tb, f_far = fb;
        }
        if (t_near > t_far) return false;
        if (f_near >= 0 && n.offer(t_near, f_near)) return true;
        return f_far >= 0 && n.offer(t_far, f_far);
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
        return surface_from_object_normal(s, r, hit, [](const Vec3&, int part) {
            Vec3 n{0.0f};
            n[part / 2] = (part & 1) ? 1.0f : -1.0f;
            return n;
        });
    }

    /// 6 faces of 4 vertices with the face normal, 2 triangles each.
    static void tessellate(const Shape& s, int, TriangleMesh& out) {
        Emitter e(s.transform, out);
        const Vec3 &lo = s.lo, &hi = s.hi;
        e.reserve(24, 12);
        for (int axis = 0; axis < 3; ++axis) {
            // (u, v, axis) is a right-handed permutation of (x, y, z).
            const int u = (axis + 1) % 3, v = (axis + 2) % 3;
            for (int side = 0; side < 2; ++side) {
                Vec3 n{0.0f};
                n[axis] = side ? 1.0f : -1.0f;
                auto corner = [&](int a, int b) {
                    Vec3 p;
                    p[axis] = side ? hi[axis] : lo[axis];
                    p[u] = a ? hi[u] : lo[u];
                    p[v] = b ? hi[v] : lo[v];
                    return e.vertex(p, n);
                };
                const uint32_t p00 = corner(0, 0), p10 = corner(1, 0), p11 = corner(1, 1),
                               p01 = corner(0, 1);
                // û × v̂ = axis: counter-clockwise from outside on the + side, reversed on the −.
                if (side)
                    e.quad(p00, p10, p11, p01);
                else
                    e.quad(p00, p01, p11, p10);
            }
        }
    }

    static double area(const Shape& s) {
        const Affine& M = s.transform.world_from_object;
        const double a = axis_length(M, 0) * (double(s.hi.x) - s.lo.x),
                     b = axis_length(M, 1) * (double(s.hi.y) - s.lo.y),
                     c = axis_length(M, 2) * (double(s.hi.z) - s.lo.z);
        return 2.0 * (a * b + b * c + c * a);
    }
};

}  // namespace luz::shapes
