// Sphere: the unit sphere at the origin in object space, placed at `center` scaled by `radius`.
// Under a similarity it is hit in world form (centre, radius: ray_sphere.h), else in object
// space in double.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "geometry/shapes/emitter.h"
#include "geometry/shapes/object_space.h"
#include "geometry/shapes/placement.h"

namespace luz::shapes {

struct sphere {
    static constexpr bool bounded = true;

    /// Placement, and the world form (centre, radius) when the transform is a similarity.
    static void place(const ObjectDesc& o, Shape& s) {
        set_transform(s, o, translation(o.center) * scaling(Vec3{o.radius}));
        const Affine& M = s.transform.world_from_object;
        if (is_similarity(M)) {
            s.world_form = true;
            s.centre = origin(M);
            s.radius = length(column(M, 0));
        }
    }

    static Bounds3 bounds(const Shape& s) {
        // The unit ball's image is an ellipsoid; its half-extent along world axis i is |row_i|
        // (the maximum of row_i·p over |p| = 1). Exact for every affine map.
        const Affine& M = s.transform.world_from_object;
        const Vec3 e{length(row(M, 0)), length(row(M, 1)), length(row(M, 2))};
        return pad({origin(M) - e, origin(M) + e});
    }

    /// The roots of object ray ro with the unit sphere, offered nearest first.
    static bool hit_object(const Ray& ro, Nearest& n) {
        double r0, r1;
        if (!ray_sphere::solve(to_d3(ro.origin), to_d3(ro.direction), 1.0, r0, r1)) return false;
        n.offer(r0, part_side) || n.offer(r1, part_side);
        return n.found;
    }

    static bool intersect(const Shape& s, const Ray& r, float t_min, float t_max, Hit& hit) {
        if (!s.world_form) return intersect_in_object_space(s, r, t_min, t_max, hit, hit_object);
        float t0, t1;
        if (!world_sphere_roots(s.centre, s.radius, r, t0, t1)) return false;
        return hit_at_roots(t0, t1, t_min, t_max, hit);
    }

    static uint32_t count_crossings(const Shape& s, const Ray& r, float t_min, float t_max,
                                    bool first_only, uint64_t& tests) {
        if (!s.world_form) {
            return count_by_repeated_hits(
                t_min, t_max, first_only, tests, [&](float t0, float t1, Hit& h) {
                    return intersect_in_object_space(s, r, t0, t1, h, hit_object);
                });
        }
        float t0 = 0, t1 = 0;
        const bool met = world_sphere_roots(s.centre, s.radius, r, t0, t1);
        return crossings_at_roots(met, t0, t1, t_min, t_max, first_only, tests);
    }

    static SurfacePoint surface_at(const Shape& s, const Ray& r, const Hit& hit) {
        if (s.world_form) {
            SurfacePoint sp;
            sp.P = r.at(hit.t);
            sp.N = unit_or(sp.P - s.centre, {0, 0, 1});
            sp.Ng = sp.N;
            return sp;
        }
        return surface_from_object_normal(s, r, hit, [](const Vec3& p, int) { return p; });
    }

    /// `level` segments around z, level/2 rings from the pole z = 1 (θ = 0) to the pole z = −1
    /// (θ = π); each pole is one vertex, so no triangle is degenerate.
    static void tessellate(const Shape& s, int level, TriangleMesh& out) {
        Emitter e(s.transform, out);
        const int n = level, rings = std::max(2, level / 2);
        const Circle circle(n);
        e.reserve(size_t(n) * (rings - 1) + 2, size_t(2) * n * (rings - 1));
        const uint32_t north = e.vertex({0, 0, 1}, {0, 0, 1});
        const uint32_t south = e.vertex({0, 0, -1}, {0, 0, -1});
        // ring(i, j): vertex of ring i (1 … rings−1) at segment j (mod n).
        std::vector<uint32_t> ring(size_t(n) * (rings - 1));
        for (int i = 1; i < rings; ++i) {
            const double theta = pi * i / rings;
            const float st = static_cast<float>(std::sin(theta)),
                        ct = static_cast<float>(std::cos(theta));
            for (int j = 0; j < n; ++j) {
                const Vec3 p{st * circle.c[j], st * circle.s[j], ct};
                ring[size_t(i - 1) * n + j] = e.vertex(p, p);
            }
        }
        auto at = [&](int i, int j) { return ring[size_t(i - 1) * n + (j % n)]; };
        // Going down θ then around φ is counter-clockwise from outside (θ̂ × φ̂ = r̂).
        for (int j = 0; j < n; ++j) {
            e.triangle(north, at(1, j), at(1, j + 1));
            for (int i = 1; i + 1 < rings; ++i)
                e.quad(at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            e.triangle(at(rings - 1, j), south, at(rings - 1, j + 1));
        }
    }

    /// 4πr² (r the mean placed radius of the x and y axes).
    static double area(const Shape& s) {
        const Affine& M = s.transform.world_from_object;
        const double r = 0.5 * (axis_length(M, 0) + axis_length(M, 1));
        return 4.0 * pi * r * r;
    }
};

}  // namespace luz::shapes
