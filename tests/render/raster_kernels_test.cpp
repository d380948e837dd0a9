// The eight-lane triangle kernel against the reference: the same fragments, bit for bit, for
// random triangles of every size (small ones in 32 bits, huge ones handed to the reference),
// both windings, orthographic and perspective, clipped pieces, and antialiasing lattices.
#include "render/raster_kernels.h"

#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <random>
#include <vector>

namespace luz {
namespace {

constexpr Fragment kEmpty{std::numeric_limits<float>::infinity(), kNoTriangle, 0, 0};

struct Case {
    Lattice lat;
    int64_t unit;  ///< fixed-point units per pixel
};

/// `count` random triangles over a tile of `lat`, each spanning up to `max_pixels`.
std::vector<RasterTriangle> random_triangles(std::mt19937& rng, const Case& c, int count,
                                             double max_pixels) {
    std::uniform_real_distribution<double> centre(-8.0, 72.0), offset(-max_pixels, max_pixels);
    std::uniform_real_distribution<float> depth(1.0f, 20.0f), inv_w(0.05f, 1.0f);
    std::vector<RasterTriangle> out;
    for (int t = 0; t < count; ++t) {
        RasterTriangle r{};
        const double cx = centre(rng), cy = centre(rng);
        for (int k = 0; k < 3; ++k) {
            r.x[k] = static_cast<int32_t>((cx + offset(rng)) * static_cast<double>(c.unit));
            r.y[k] = static_cast<int32_t>((cy + offset(rng)) * static_cast<double>(c.unit));
            r.depth[k] = depth(rng);
            r.inv_w[k] = inv_w(rng);
        }
        if (t % 7 == 3) {  // edges on lattice points: the top-left rule decides
            r.x[1] = r.x[0];
            r.y[2] = r.y[0];
        }
        r.triangle = static_cast<uint32_t>(t);
        r.clip = t % 5 == 0 ? 0 : -1;
        out.push_back(r);
    }
    return out;
}

void expect_same_fragments(const Case& c, double max_pixels, bool perspective, unsigned seed,
                           int count = 300) {
    std::mt19937 rng(seed);
    const std::vector<RasterTriangle> tris = random_triangles(rng, c, count, max_pixels);
    const std::array<Vec3, 3> clip_bary = {Vec3{0.7f, 0.2f, 0.1f}, Vec3{0.1f, 0.6f, 0.3f},
                                           Vec3{0.25f, 0.25f, 0.5f}};
    const size_t points = static_cast<size_t>(c.lat.w) * c.lat.h;
    std::vector<Fragment> reference(points, kEmpty), lanes(points, kEmpty);
    std::vector<uint32_t> tests(points, 0);
    std::vector<float> depths(points + 8, std::numeric_limits<float>::infinity());
    for (const RasterTriangle& r : tris) {
        const auto* cb = r.clip >= 0 ? &clip_bary : nullptr;
        rasterize_triangle_reference(perspective, r, cb, c.lat, reference.data(), tests.data());
        rasterize_triangle_lanes(perspective, r, cb, c.lat, lanes.data(), depths.data());
    }
    size_t covered = 0, differ = 0;
    for (size_t i = 0; i < points; ++i) {
        covered += reference[i].triangle != kNoTriangle;
        differ += std::memcmp(&reference[i], &lanes[i], sizeof(Fragment)) != 0;
        differ += std::memcmp(&depths[i], &lanes[i].depth, sizeof(float)) != 0;
    }
    EXPECT_EQ(differ, 0u) << "of " << points << " points";
    for (size_t i = points; i < depths.size(); ++i)  // the padding is left as it was
        EXPECT_EQ(depths[i], std::numeric_limits<float>::infinity());
    EXPECT_GT(covered, points / 4);  // the comparison is of something
}

// No antialiasing: pixel centres, 256 units per pixel, a 64 × 64 tile.
const Case kPixels{{128, 128, 256, 64, 64}, 256};
// Grid antialiasing 3 × 3: a finer lattice of a larger unit.
const Case kGrid{{24 * 2 + 8, 24 * 2 + 8, 16, 40 * 3, 37 * 3}, 48};
// Pixel corners (adaptive's first pass): integer points, a 65 × 65 lattice.
const Case kCorners{{0, 0, 256, 65, 65}, 256};

TEST(RasterKernels, LanesMatchReferenceOnSmallTriangles) {
    expect_same_fragments(kPixels, 12, false, 1);
    expect_same_fragments(kPixels, 12, true, 2);
    expect_same_fragments(kPixels, 3, false, 3, 3000);
}

TEST(RasterKernels, LanesMatchReferenceOnTileSizedTriangles) {
    expect_same_fragments(kPixels, 70, false, 4);
    expect_same_fragments(kPixels, 70, true, 5);
}

TEST(RasterKernels, LanesHandHugeTrianglesToTheReference) {
    // Boxes of thousands of pixels: their edge functions need 64 bits.
    expect_same_fragments(kPixels, 4000, false, 6);
    expect_same_fragments(kPixels, 4000, true, 7);
}

TEST(RasterKernels, LanesMatchReferenceOnAntialiasingLattices) {
    expect_same_fragments(kGrid, 10, false, 8);
    expect_same_fragments(kGrid, 10, true, 9);
    expect_same_fragments(kCorners, 20, false, 10);
    expect_same_fragments(kCorners, 20, true, 11);
}

}  // namespace
}  // namespace luz
