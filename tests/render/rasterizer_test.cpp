// The zbuffer's rasterizer on its own: a fan of triangles covers every pixel centre inside it
// exactly once (top-left rule), and a fragment's barycentrics give back the point it stands for.
#include "render/rasterizer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

namespace luz {
namespace {

constexpr int kSize = 48;

Camera front_camera() {
    CameraDesc d;
    d.projection = Projection::orthographic;
    d.position = {0, 0, 10};
    d.look_at = {0, 0, 0};
    d.view_height = 2;  // the image spans [−1, 1]²
    return Camera::from(d, kSize, kSize);
}

/// A fan of `n` triangles around `c`, its rim a regular n-gon of radius `r` in the plane z = 0.
TriangleMesh fan(Vec3 c, float r, int n) {
    TriangleMesh m;
    m.positions.push_back(c);
    for (int k = 0; k < n; ++k) {
        const double a = 2 * std::numbers::pi * k / n + 0.1;
        m.positions.push_back(
            c + Vec3{static_cast<float>(r * std::cos(a)), static_cast<float>(r * std::sin(a)), 0});
    }
    m.normals.assign(m.positions.size(), Vec3{0, 0, 1});
    for (int k = 0; k < n; ++k) {
        for (uint32_t i : {0u, uint32_t(1 + k), uint32_t(1 + (k + 1) % n)}) m.indices.push_back(i);
    }
    return m;
}

/// The fragments of the pixel centres of the whole image (one tile).
std::vector<Fragment> rasterize_all(const TriangleMesh& mesh) {
    const Rasterizer raster(mesh, front_camera(), kSize, kSize, RasterLayout{}, 1);
    EXPECT_EQ(raster.tile_count(), 1u);
    std::vector<Fragment> frags(kSize * kSize);
    raster.rasterize(0, raster.centres(raster.tile_rect(0)), frags.data());
    return frags;
}

TEST(Rasterizer, FanCoversEachPixelCentreInsideOnce) {
    const Vec3 c{0.07f, -0.03f, 0};
    const float r = 0.9f;
    const int n = 17;
    const TriangleMesh whole = fan(c, r, n);
    std::vector<int> count(kSize * kSize, 0);
    for (int t = 0; t < n; ++t) {  // each triangle alone: coverage adds up
        TriangleMesh one = whole;
        one.indices.assign(whole.indices.begin() + 3 * t, whole.indices.begin() + 3 * t + 3);
        const std::vector<Fragment> frags = rasterize_all(one);
        for (size_t p = 0; p < frags.size(); ++p) count[p] += frags[p].triangle != kNoTriangle;
    }
    const float inner = r * static_cast<float>(std::cos(std::numbers::pi / n)) - 0.05f;
    for (int j = 0; j < kSize; ++j) {
        for (int i = 0; i < kSize; ++i) {
            const float x = 2 * (i + 0.5f) / kSize - 1, y = 1 - 2 * (j + 0.5f) / kSize;
            const int k = count[j * kSize + i];
            ASSERT_LE(k, 1) << "pixel " << i << ", " << j << " covered twice";
            const float d = std::hypot(x - c.x, y - c.y);
            if (d < inner) {
                ASSERT_EQ(k, 1) << i << ", " << j;
            } else if (d > r) {
                ASSERT_EQ(k, 0) << i << ", " << j;
            }
        }
    }
}

TEST(Rasterizer, BarycentricsGiveBackThePixelCentre) {
    const TriangleMesh mesh = fan({0.07f, -0.03f, 0}, 0.9f, 17);
    const std::vector<Fragment> frags = rasterize_all(mesh);
    int covered = 0;
    for (int j = 0; j < kSize; ++j) {
        for (int i = 0; i < kSize; ++i) {
            const Fragment& f = frags[j * kSize + i];
            if (f.triangle == kNoTriangle) continue;
            ++covered;
            const uint32_t* idx = &mesh.indices[3 * f.triangle];
            const Vec3 p = mesh.positions[idx[0]] * (1 - f.b1 - f.b2) +
                           mesh.positions[idx[1]] * f.b1 + mesh.positions[idx[2]] * f.b2;
            EXPECT_NEAR(p.x, 2 * (i + 0.5f) / kSize - 1, 1e-4f);
            EXPECT_NEAR(p.y, 1 - 2 * (j + 0.5f) / kSize, 1e-4f);
            EXPECT_NEAR(f.depth, 10.0f, 1e-4f);  // the view depth of the plane z = 0
        }
    }
    EXPECT_GT(covered, kSize * kSize / 2);
}

}  // namespace
}  // namespace luz
