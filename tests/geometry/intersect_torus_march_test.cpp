// intersect() on the torus against a brute-force march of its signed distance in double.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "geometry/shapes.h"
#include "intersect_fixtures.h"

namespace luz::test {
namespace {

/// Brute force on the object-space ray in double: sample the torus's signed distance along
/// the ray with steps no longer than its value (a 1-Lipschitz function cannot change sign
/// within that step, so no crossing is skipped), down to 1e-7, and bisect the first sign
/// change. min_abs is the closest the samples came to the surface.
bool march_torus(const Ray& ro, double m, double t_min, double t_max, double& t_hit,
                 double& min_abs) {
    const double o[3] = {ro.origin.x, ro.origin.y, ro.origin.z};
    const double d[3] = {ro.direction.x, ro.direction.y, ro.direction.z};
    const double dl = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    const auto sd = [&](double s) {  // s: distance along the unit direction
        const double x = o[0] + s * d[0] / dl, y = o[1] + s * d[1] / dl, z = o[2] + s * d[2] / dl;
        return std::hypot(std::hypot(x, y) - 1.0, z) - m;
    };
    const auto radius2 = [&](double s) {
        double r2 = 0;
        for (int k = 0; k < 3; ++k) r2 += (o[k] + s * d[k] / dl) * (o[k] + s * d[k] / dl);
        return r2;
    };
    const double s_end = std::min(t_max * dl, 1e9);
    double s = t_min * dl, f = sd(s);
    min_abs = std::fabs(f);
    for (long i = 0; i < 50'000'000; ++i) {
        double s1 = std::min(s + std::max(std::fabs(f), 1e-7), s_end);
        const double f1 = sd(s1);
        min_abs = std::min(min_abs, std::fabs(f1));
        if ((f > 0) != (f1 > 0)) {
            double lo = s, hi = s1;
            for (int k = 0; k < 80; ++k) {
                const double mid = 0.5 * (lo + hi);
                ((sd(mid) > 0) == (f > 0) ? lo : hi) = mid;
            }
            t_hit = 0.5 * (lo + hi) / dl;
            return true;
        }
        // past the torus and moving away from it: nothing more
        if (s1 >= s_end || (radius2(s1) > (2 + m) * (2 + m) && radius2(s1) > radius2(s)))
            return false;
        s = s1;
        f = f1;
    }
    return false;
}

TEST(Intersect, TorusMatchesBruteForceMarch) {
    std::mt19937 rng(2024);
    std::uniform_real_distribution<float> U(0, 1);
    std::normal_distribution<float> N01;
    const auto unit_vector = [&] { return normalize(Vec3{N01(rng), N01(rng), N01(rng)}); };
    std::vector<Shape> tori;
    for (const float minor : {0.35f, 0.1f, 1.0f, 0.9f * 1.2f}) {
        ObjectDesc o = torus_desc();  // major radius 1.2
        o.minor_radius = minor;
        for (const NamedTransform& tr : user_transforms())
            tori.push_back(make_shape(with_transform(o, tr.affine), 0));
    }
    int hits = 0, compared = 0, ambiguous = 0, mismatched = 0;
    double worst = 0;
    for (int i = 0; i < 20000; ++i) {
        const Shape& s = tori[i % tori.size()];
        const float m = s.minor;
        Vec3 o, d = unit_vector() * (0.3f + 2 * U(rng));
        switch (i / 5000) {
            case 0:  // anywhere around it, inside the hole and the tube included
                o = Vec3{4 * U(rng) - 2, 4 * U(rng) - 2, 2 * U(rng) - 1};
                break;
            case 1: {  // from inside the tube
                const float phi = 2 * float(pi) * U(rng);
                o = Vec3{std::cos(phi), std::sin(phi), 0} + unit_vector() * (0.95f * m * U(rng));
                break;
            }
            case 2: {  // grazing: tangent to the surface, moved off it by ±[1e-6, 1e-2]·m
                const SurfaceSample smp = sample_surface(s, rng);
                const Vec3 tangent = normalize(cross(smp.n, unit_vector()));
                const float delta = m * std::pow(10.0f, -6 + 4 * U(rng)) * (U(rng) < 0.5f ? -1 : 1);
                d = tangent * length(d);
                o = smp.p + smp.n * delta - d * (3 * U(rng));
                break;
            }
            default:  // from far away, aimed at the torus
                o = unit_vector() * (20 + 500 * U(rng));
                d = normalize(Vec3{2 * U(rng) - 1, 2 * U(rng) - 1, m * (2 * U(rng) - 1)} - o) *
                    length(d);
                break;
        }
        const Ray r = world_ray(s, o, d);
        const float t_min = (i % 7 == 0) ? 0.5f * U(rng) : 0.0f;
        const float t_max = (i % 11 == 0) ? 1 + 3 * U(rng) : inf;
        Hit h;
        const bool hit = intersect(s, r, t_min, t_max, h);
        double t_ref = 0, min_abs = 0;
        // the same object-space ray the intersector sees
        const bool ref = march_torus(s.transform.to_object(r), m, t_min, t_max, t_ref, min_abs);
        if (hit != ref) {
            // only acceptable where the ray touches the surface to within double rounding
            if (min_abs < 1e-9) {
                ++ambiguous;
            } else {
                ++mismatched;
                if (mismatched < 10)
                    ADD_FAILURE() << "ray " << i << ": intersect " << hit << ", march " << ref
                                  << " (t " << (hit ? h.t : t_ref) << ", closest " << min_abs
                                  << ")";
            }
            continue;
        }
        if (!hit) continue;
        ++hits;
        ++compared;
        const double err = std::fabs(h.t - t_ref) / std::max(t_ref, 1e-3);
        worst = std::max(worst, err);
        EXPECT_LT(err, 1e-3) << "ray " << i << ": t " << h.t << " vs " << t_ref;
        EXPECT_TRUE(h.t > t_min && h.t < t_max);
        const SurfacePoint sp = surface_at(s, r, h);
        EXPECT_TRUE(unit(sp.N) && unit(sp.Ng));
    }
    EXPECT_EQ(mismatched, 0);
    EXPECT_LE(ambiguous, 5);
    EXPECT_GT(hits, 8000);  // the sample exercises hits as well as misses
    EXPECT_LT(worst, 1e-5);
    std::printf("torus: %d hits of 20000, %d ambiguous, worst relative t error %g\n", hits,
                ambiguous, worst);
    (void)compared;
}

}  // namespace
}  // namespace luz::test
