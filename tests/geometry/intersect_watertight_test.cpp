// Watertight triangles: rays through an edge or a vertex shared by triangles never slip through.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "geometry/ray_triangle.h"
#include "geometry/shapes.h"
#include "intersect_fixtures.h"

namespace luz::test {
namespace {

Shape triangle_shape(const Vec3& a, const Vec3& b, const Vec3& c, const Affine& transform) {
    ObjectDesc o;
    o.type = ShapeType::triangle;
    o.vertices = {a, b, c};
    o.transform = transform;
    return make_shape(o, 0);
}

TEST(Intersect, RaysThroughASharedEdgeOrVertexNeverSlipThrough) {
    std::mt19937 rng(99);
    std::uniform_real_distribution<float> U(0, 1);
    const auto sign = [&] { return U(rng) < 0.5f ? -1.0f : 1.0f; };
    // Two triangles on edge a–b, consistently wound, bent 3° along it; the rays cross their
    // plane at 10° or more, so in projection they lie on both sides of the edge (no fold).
    const Vec3 a{0.1f, 0.2f, 0.3f}, b{1.7f, -0.3f, 0.9f}, c{0.4f, 1.9f, -0.2f};
    const Vec3 n = normalize(cross(b - a, c - a)), mid = (a + b) * 0.5f;
    const Vec3 d = mid - (c - mid) + n * 0.1f;
    const Vec3 u = normalize(b - a), w = cross(n, u);
    for (const NamedTransform& tr : user_transforms()) {
        SCOPED_TRACE(tr.name);
        const Shape t1 = triangle_shape(a, b, c, tr.affine),
                    t2 = triangle_shape(b, a, d, tr.affine);
        int neither = 0;
        for (int i = 0; i < 20000; ++i) {
            const Vec3 e = a + (b - a) * U(rng);  // on the edge up to rounding
            const Vec3 o =
                e + n * (sign() * (2 + 8 * U(rng))) + u * (10 * U(rng) - 5) + w * (10 * U(rng) - 5);
            const Ray r = world_ray(t1, o, (e - o) * (0.1f + U(rng)));  // the same transform
            Hit h1, h2;
            neither += !intersect(t1, r, 0, inf, h1) && !intersect(t2, r, 0, inf, h2);
        }
        EXPECT_EQ(neither, 0);
        // a closed fan of six triangles around a shared vertex, slopes ≤ 0.2
        const Vec3 centre{0.3f, -0.7f, 0.2f};
        const auto rim = [&](int j) {
            const float phi = 2 * float(pi) / 6 * (j % 6) + 0.2f * std::sin(float(j % 6));
            return centre + Vec3{std::cos(phi), std::sin(phi), 0.1f * std::sin(3 * phi)};
        };
        std::vector<Shape> fan;
        for (int k = 0; k < 6; ++k)
            fan.push_back(triangle_shape(centre, rim(k), rim(k + 1), tr.affine));
        int missed = 0;
        for (int i = 0; i < 5000; ++i) {
            const Vec3 o =
                centre + Vec3{10 * U(rng) - 5, 10 * U(rng) - 5, sign() * (3 + 7 * U(rng))};
            const Ray r = world_ray(fan[0], o, centre - o);
            bool any = false;
            Hit h;
            for (const Shape& f : fan) any = any || intersect(f, r, 0, inf, h);
            missed += !any;
        }
        EXPECT_EQ(missed, 0);
    }
}

// prepare_watertight() chooses its axes by arithmetic: the same as the branches it replaced on
// every direction, ties between components, −0, NaN and d_z < 0 (the swap) included.
TEST(Intersect, WatertightRayAxesAreThoseOfTheDominantComponentRule) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float values[] = {0.0f, -0.0f, 0.5f, -0.5f, 1.0f, -1.0f, 2.0f, -2.0f, nan};
    int checked = 0;
    for (float x : values) {
        for (float y : values) {
            for (float z : values) {
                const Ray r{{1.0f, 2.0f, 3.0f}, {x, y, z}};
                const float d[3] = {x, y, z};
                const float ax = std::fabs(x), ay = std::fabs(y), az = std::fabs(z);
                const int kz = ax > ay ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2);
                int kx = kz == 2 ? 0 : kz + 1;
                int ky = kx == 2 ? 0 : kx + 1;
                if (d[kz] < 0) std::swap(kx, ky);
                const WatertightRay w = prepare_watertight(r);
                SCOPED_TRACE(std::to_string(x) + " " + std::to_string(y) + " " + std::to_string(z));
                EXPECT_EQ(w.kz, kz);
                EXPECT_EQ(w.kx, kx);
                EXPECT_EQ(w.ky, ky);
                ++checked;
            }
        }
    }
    EXPECT_EQ(checked, 9 * 9 * 9);
}

}  // namespace
}  // namespace luz::test
