// Torus: major radius 1 around +z in the z = 0 plane, minor radius `minor` (< 1) in object space,
// placed at `center` around `axis` scaled by `major_radius`; hit by the first root of its
// quartic (quartic.h) in double.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "geometry/shapes/emitter.h"
#include "geometry/shapes/object_space.h"
#include "geometry/shapes/placement.h"
#include "geometry/shapes/quartic.h"

namespace luz::shapes {

struct torus {
    static constexpr bool bounded = true;

    static void place(const ObjectDesc& o, Shape& s) {
        const float R = o.major_radius;
        set_transform(s, o, frame_along(o.axis, R, R, R, o.center));
        s.minor = o.minor_radius / o.major_radius;
    }

    static Bounds3 bounds(const Shape& s) {
        // The major circle's bounds grown by the tube's (an ellipsoid of radius `minor`): exact
        // for similarity transforms, conservative otherwise.
        const Affine& M = s.transform.world_from_object;
        const Vec3 U = column(M, 0), V = column(M, 1);
        const Bounds3 b = ellipse_bounds(origin(M), U, V);
        const Vec3 e = Vec3{length(row(M, 0)), length(row(M, 1)), length(row(M, 2))} * s.minor;
        return pad({b.lo - e, b.hi + e});
    }

    /// (|p|² + 1 − m²)² − 4(x² + y²) = 0.
    static bool hit_object(const Shape& s, const Ray& ro, Nearest& n) {
        const D3 o = to_d3(ro.origin), d = to_d3(ro.direction);
        const double dl2 = dot(d, d);
        if (!(dl2 > 0)) return false;
        const double dl = std::sqrt(dl2);
        const D3 dn{d.x / dl, d.y / dl, d.z / dl};
        const double m = s.minor, k = 1.0 - m * m;

        // Bounding sphere (radius 1 + m, a little margin): the search runs over the part of the
        // ray inside it, with distances x along the unit direction from its first point p0.
        const double Rb = (1.0 + m) * 1.001;
        const double b = dot(o, dn);
        const D3 l = along(o, dn, -b);
        const double h2 = Rb * Rb - dot(l, l);
        if (!(h2 > 0)) return false;
        const double h = std::sqrt(h2);
        const double s_lo = std::fmax(-b - h, double(n.t_min) * dl);
        const double s_hi = std::fmin(-b + h, double(n.best) * dl);
        if (!(s_lo < s_hi)) return false;

        // Moving the origin to p0 (inside or on the bounding sphere) keeps the quartic's
        // coefficients of order 1 however far the ray starts: the conditioning that matters.
        const D3 p0 = along(o, dn, s_lo);
        const double A = dot(dn, dn), B = dot(p0, dn), E = dot(p0, p0) + k;
        const double alpha = dn.x * dn.x + dn.y * dn.y, beta = p0.x * dn.x + p0.y * dn.y,
                     gamma = p0.x * p0.x + p0.y * p0.y;
        // (A·x² + 2B·x + E)² − 4(α·x² + 2β·x + γ)
        const Quartic q{A * A, 4 * A * B, 4 * B * B + 2 * A * E - 4 * alpha, 4 * B * E - 8 * beta,
                        E * E - 4 * gamma};
        const double x = first_root(q, s_hi - s_lo);
        if (!(x >= 0)) return false;
        return n.offer((s_lo + x) / dl, part_side);
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
        return surface_from_object_normal(s, r, hit, [](const Vec3& p, int) {
            // ∇f ∝ p − (nearest point of the major circle)
            const float rr = std::sqrt(p.x * p.x + p.y * p.y);
            return rr > 0 ? p - Vec3{p.x / rr, p.y / rr, 0} : Vec3{0, 0, 1};
        });
    }

    /// `level` segments around the major circle (angle u), max(3, level/2) around the tube
    /// (angle v); p = ((1 + r·cos v)·cos u, (1 + r·cos v)·sin u, r·sin v),
    /// n = (cos v·cos u, cos v·sin u, sin v).
    static void tessellate(const Shape& s, int level, TriangleMesh& out) {
        Emitter e(s.transform, out);
        const float r = s.minor;
        const int nu = level, nv = std::max(3, level / 2);
        const Circle cu(nu), cv(nv);
        e.reserve(size_t(nu) * nv, 2 * size_t(nu) * nv);
        uint32_t first = 0;
        for (int j = 0; j < nu; ++j) {
            for (int k = 0; k < nv; ++k) {
                const float rho = 1.0f + r * cv.c[k];
                const uint32_t i = e.vertex({rho * cu.c[j], rho * cu.s[j], r * cv.s[k]},
                                            {cv.c[k] * cu.c[j], cv.c[k] * cu.s[j], cv.s[k]});
                if (j == 0 && k == 0) first = i;
            }
        }
        auto at = [&](int j, int k) { return first + uint32_t((j % nu) * nv + (k % nv)); };
        // ∂p/∂u × ∂p/∂v ∝ n: around the major circle first, then around the tube.
        for (int j = 0; j < nu; ++j)
            for (int k = 0; k < nv; ++k)
                e.quad(at(j, k), at(j + 1, k), at(j + 1, k + 1), at(j, k + 1));
    }

    /// 4π²Rr.
    static double area(const Shape& s) {
        const Affine& M = s.transform.world_from_object;
        const double r = 0.5 * (axis_length(M, 0) + axis_length(M, 1));
        return 4.0 * pi * pi * r * (s.minor * r);
    }
};

}  // namespace luz::shapes
