// The antialiasing samplers of docs/SCENES.md#antialiasing on synthetic colour functions: grid
// positions and box coverage, tent weights, jitter determinism, adaptive splitting and its sample
// count.
#include "render/sampler.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <map>
#include <utility>

#include "same_bits.h"

namespace luz {
namespace {

struct NoSamplerCounters {};

AntialiasDesc grid(int samples, AaFilter filter = AaFilter::box, bool jitter = false) {
    AntialiasDesc aa;
    aa.mode = AaMode::grid;
    aa.samples = samples;
    aa.filter = filter;
    aa.jitter = jitter;
    return aa;
}

AntialiasDesc adaptive(float threshold, int max_level) {
    AntialiasDesc aa;
    aa.mode = AaMode::adaptive;
    aa.threshold = threshold;
    aa.max_level = max_level;
    return aa;
}

/// Renders a w×h image of `colour(x, y)` with `aa`. One type of colour function for every
/// test: sample_image() is compiled once, not once per test's lambda.
using ColourFunction = std::function<Rgb(float, float)>;
Image run(const AntialiasDesc& aa, int w, int h, const ColourFunction& colour,
          SamplerCounts* counts = nullptr, int threads = 1, AaMask* mask = nullptr) {
    Image out(w, h);
    RenderControl control;
    control.threads = threads;
    std::vector<NoSamplerCounters> counters;
    const SamplerCounts c = sample_image(
        aa, w, h, control, [&](float x, float y, NoSamplerCounters&) { return colour(x, y); }, out,
        counters, mask);
    if (counts) *counts = c;
    return out;
}

TEST(GridSampler, SamplesSitAtTheCentresOfTheirCells) {
    GridSpec g;
    g.s = 4;
    g.width = 10;
    g.height = 10;
    float x, y;
    g.position(3, 7, 0, 0, x, y);
    EXPECT_FLOAT_EQ(x, 3.125f);
    EXPECT_FLOAT_EQ(y, 7.125f);
    g.position(3, 7, 3, 1, x, y);
    EXPECT_FLOAT_EQ(x, 3.875f);
    EXPECT_FLOAT_EQ(y, 7.375f);
}

// A straight edge crossing pixel (1, 1) at a known coverage: the box filter gives the mix of
// the two colours in that proportion within 1/s². The edge x = c0 + y/s is sheared by one
// sample column over the pixel, so that the s² samples fall at s² distinct distances from it.
TEST(GridSampler, BoxFilterGivesAStraightEdgesCoverageWithinOneOverSSquared) {
    const Rgb A{1.0f, 0.0f, 0.0f}, B{0.0f, 0.0f, 1.0f};
    for (int s : {1, 2, 3, 4, 8, 16}) {
        for (float c0 = 0.0f; c0 <= 1.0f - 1.0f / s; c0 += 0.037f) {
            auto colour = [&](float x, float y) {
                const float lx = x - 1.0f, ly = y - 1.0f;  // pixel (1, 1)
                return lx < c0 + ly / s ? A : B;
            };
            const Image img = run(grid(s * s), 3, 3, colour);
            const float coverage = c0 + 0.5f / s;  // area left of the edge inside the pixel
            const Rgb expected = A * coverage + B * (1.0f - coverage);
            EXPECT_NEAR(img.at(1, 1).x, expected.x, 1.0f / (s * s) + 1e-6f) << "s " << s;
            EXPECT_NEAR(img.at(1, 1).z, expected.z, 1.0f / (s * s) + 1e-6f) << "s " << s;
        }
    }
}

TEST(GridSampler, OneSampleIsThePixelCentre) {
    auto colour = [](float x, float y) { return Rgb{x, y, 0.0f}; };
    const Image a = run(grid(1), 7, 5, colour);
    AntialiasDesc none;
    const Image b = run(none, 7, 5, colour);
    EXPECT_TRUE(same_bits(a, b));
    EXPECT_EQ(a.at(2, 3), (Rgb{2.5f, 3.5f, 0.0f}));
}

// docs/SCENES.md#antialiasing: tent weights max(0, 1−|dx|)·max(0, 1−|dy|) over the pixel's and its
// 8 neighbours' samples sum to s² on the regular grid, so that divided by their sum they sum to one
// — and a constant image stays that constant everywhere, borders included.
TEST(GridSampler, TentWeightsSumToOne) {
    for (int s = 1; s <= 16; ++s) {
        GridSpec g;
        g.s = s;
        g.width = g.height = 3;
        double sum = 0;
        for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 3; ++i)
                for (int b = 0; b < s; ++b)
                    for (int a = 0; a < s; ++a) {
                        float x, y;
                        g.position(i, j, a, b, x, y);
                        sum += tent_weight(x - 1.5f, y - 1.5f);
                    }
        EXPECT_NEAR(sum, s * s, 1e-4 * s * s) << "s " << s;
    }
    const Rgb c{0.3f, 0.6f, 0.9f};
    for (bool jitter : {false, true}) {
        const Image img =
            run(grid(9, AaFilter::tent, jitter), 37, 21, [&](float, float) { return c; });
        for (const Rgb& p : img.pixels) {
            EXPECT_NEAR(p.x, c.x, 1e-6f);
            EXPECT_NEAR(p.y, c.y, 1e-6f);
            EXPECT_NEAR(p.z, c.z, 1e-6f);
        }
    }
}

// The tent is symmetric: a linear ramp gives the value at the pixel centre away from the border;
// it reaches into the neighbours: next to a vertical step the pixel takes some of the other side.
TEST(GridSampler, TentFilterWeighsTheNeighbours) {
    const Image ramp = run(grid(16, AaFilter::tent), 40, 20, [](float x, float y) {
        return Rgb{x, y, 0.0f};
    });
    for (int j = 1; j < 19; ++j)
        for (int i = 1; i < 39; ++i) {
            EXPECT_NEAR(ramp.at(i, j).x, i + 0.5f, 1e-4f);
            EXPECT_NEAR(ramp.at(i, j).y, j + 0.5f, 1e-4f);
        }
    auto step = [](float x, float) { return Rgb{x < 20.0f ? 1.0f : 0.0f}; };
    const Image box = run(grid(16), 40, 20, step),
                tent = run(grid(16, AaFilter::tent), 40, 20, step);
    EXPECT_EQ(box.at(19, 5).x, 1.0f);
    EXPECT_EQ(box.at(20, 5).x, 0.0f);
    EXPECT_NEAR(tent.at(19, 5).x, 0.875f, 1e-3f);  // 1 − ∫ of the tent beyond half a pixel
    EXPECT_NEAR(tent.at(20, 5).x, 0.125f, 1e-3f);
    EXPECT_EQ(tent.at(10, 5).x, 1.0f);
}

TEST(GridSampler, JitterStaysInsideTheCellAndIsTheSameForAnyThreadCountAndRun) {
    GridSpec g;
    g.s = 4;
    g.jitter = true;
    g.width = 50;
    g.height = 50;
    bool moved = false;
    for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) {
            float x, y;
            g.position(17, 33, a, b, x, y);
            EXPECT_GE(x, 17 + a / 4.0f);
            EXPECT_LT(x, 17 + (a + 1) / 4.0f);
            EXPECT_GE(y, 33 + b / 4.0f);
            EXPECT_LT(y, 33 + (b + 1) / 4.0f);
            moved |= x != 17 + (a + 0.5f) / 4.0f;
        }
    EXPECT_TRUE(moved);
    auto colour = [](float x, float y) {
        return Rgb{std::sin(x * y * 0.1f), std::fmod(x * 0.37f + y, 1.0f), 0.5f};
    };
    for (AaFilter filter : {AaFilter::box, AaFilter::tent}) {
        const Image one = run(grid(16, filter, true), 53, 41, colour, nullptr, 1);
        const Image two = run(grid(16, filter, true), 53, 41, colour, nullptr, 2);
        const Image three = run(grid(16, filter, true), 53, 41, colour, nullptr, 3);
        const Image again = run(grid(16, filter, true), 53, 41, colour, nullptr, 3);
        const Image regular = run(grid(16, filter, false), 53, 41, colour, nullptr, 1);
        EXPECT_TRUE(same_bits(one, two));
        EXPECT_TRUE(same_bits(one, three));
        EXPECT_TRUE(same_bits(three, again));
        EXPECT_FALSE(same_bits(one, regular));
    }
}

TEST(GridSampler, CountsOneSamplePerCellAndOnlyTheTentRingSamplesThatWeigh) {
    SamplerCounts box, tent;
    run(
        grid(4), 40, 24, [](float, float) { return Rgb{}; }, &box);
    EXPECT_EQ(box.samples, 40u * 24 * 4);
    run(
        grid(4, AaFilter::tent), 40, 24, [](float, float) { return Rgb{}; }, &tent);
    EXPECT_GT(tent.samples, box.samples);  // tiles recompute the half-pixel ring they need
    EXPECT_LT(tent.samples, box.samples * 3 / 2);
}

// docs/SCENES.md#antialiasing: "one sample per pixel corner first (corners are shared by
// neighbouring pixels)": a flat image costs exactly (W+1)·(H+1) samples, whatever the tiles.
TEST(AdaptiveSampler, FlatRegionsCostOneSamplePerPixelCorner) {
    SamplerCounts counts;
    AaMask mask;
    const Image img = run(
        adaptive(0.0f, 3), 37, 23, [](float, float) { return Rgb{0.25f}; }, &counts, 2, &mask);
    EXPECT_EQ(counts.samples, 38u * 24);
    EXPECT_EQ(counts.pixels_refined, 0u);
    for (const Rgb& p : img.pixels) EXPECT_EQ(p, Rgb{0.25f});
    for (uint8_t level : mask.level) EXPECT_EQ(level, 0);
}

// docs/SCENES.md#antialiasing: "largest per-channel difference, on values clamped to [0,1]".
TEST(AdaptiveSampler, CornerDifferenceIsTheLargestChannelRangeOfClampedValues) {
    EXPECT_EQ(corner_difference(Rgb{0.2f}, Rgb{0.2f}, Rgb{0.2f}, Rgb{0.2f}), 0.0f);
    EXPECT_FLOAT_EQ(corner_difference({0.1f, 0.5f, 0.0f}, {0.3f, 0.5f, 0.0f}, {0.2f, 0.9f, 0.0f},
                                      {0.2f, 0.6f, 0.0f}),
                    0.4f);
    EXPECT_EQ(corner_difference(Rgb{2.0f}, Rgb{1.0f}, Rgb{5.0f}, Rgb{1.5f}), 0.0f);  // all white
    EXPECT_FLOAT_EQ(corner_difference(Rgb{-1.0f}, Rgb{0.5f}, Rgb{0.0f}, Rgb{-3.0f}), 0.5f);
    EXPECT_FLOAT_EQ(corner_difference(Rgb{-1.0f}, Rgb{9.0f}, Rgb{0.5f}, Rgb{0.5f}), 1.0f);
}

// A pixel with corners A, A (left) and B, B (right) of an edge at x = 0.3: max_level 0 keeps
// the mean of the corners; max_level 1 splits once into 4 sub-pixels.
TEST(AdaptiveSampler, SplitsUpToMaxLevelAndAveragesTheParts) {
    const Rgb A{1.0f, 0.0f, 0.0f}, B{0.0f, 0.0f, 1.0f};
    auto edge = [&](float x, float) { return x < 0.3f ? A : B; };
    SamplerCounts counts;
    EXPECT_EQ(run(adaptive(0.1f, 0), 1, 1, edge, &counts).at(0, 0), (A + B) * 0.5f);
    EXPECT_EQ(counts.samples, 4u);
    EXPECT_EQ(counts.pixels_refined, 0u);
    // Level 1: the left sub-pixels have corners A, B, A, B; the right ones B only.
    EXPECT_EQ(run(adaptive(0.1f, 1), 1, 1, edge, &counts).at(0, 0), (A + B * 3.0f) * 0.25f);
    EXPECT_EQ(counts.samples, 4u + 5u);  // the 5 new corners, each once
    EXPECT_EQ(counts.pixels_refined, 1u);
    // Level 2: only the two left sub-pixels split again: 5 + 4 new corners (one is shared).
    // Their parts are A for x in [0, 0.25] and (A+B)/2 for [0.25, 0.5]: red = (2 + 1)/4 / 2.
    AaMask mask;
    const Rgb v2 = run(adaptive(0.1f, 2), 1, 1, edge, &counts, 1, &mask).at(0, 0);
    EXPECT_EQ(counts.samples, 4u + 5u + 9u);
    EXPECT_NEAR(v2.x, 0.375f, 1e-6f);
    EXPECT_EQ(mask.level[0], 2);
    // "strictly more than threshold": corners differing by exactly the threshold stay whole.
    EXPECT_EQ(run(adaptive(1.0f, 3), 1, 1, edge, &counts).at(0, 0), (A + B) * 0.5f);
    EXPECT_EQ(counts.pixels_refined, 0u);
}

// "each new corner sampled once": within a tile, sub-corners on the edge between two refined
// pixels are shared, so no point is ever asked for twice.
TEST(AdaptiveSampler, EachCornerIsSampledOnce) {
    std::map<std::pair<float, float>, int> calls;
    auto disc = [&](float x, float y) {
        ++calls[{x, y}];
        const float dx = x - 8.1f, dy = y - 7.9f;
        return Rgb{dx * dx + dy * dy < 30.0f ? 1.0f : 0.0f};
    };
    SamplerCounts counts;
    AaMask mask;
    run(adaptive(0.1f, 4), 16, 16, disc, &counts, 1, &mask);  // one tile
    EXPECT_GT(counts.pixels_refined, 20u);
    EXPECT_EQ(counts.samples, calls.size());
    for (const auto& [point, n] : calls) EXPECT_EQ(n, 1) << point.first << ", " << point.second;
    size_t refined = 0;
    for (uint8_t level : mask.level) {
        refined += level > 0;
        EXPECT_LE(level, 4);
    }
    EXPECT_EQ(refined, counts.pixels_refined);
}

TEST(AdaptiveSampler, SameBitsForAnyThreadCount) {
    auto colour = [](float x, float y) {
        return Rgb{std::sin(x * 0.3f) > 0 ? 1.0f : 0.0f, std::fmod(x * y * 0.01f, 1.0f), 0.2f};
    };
    SamplerCounts c1, c3;
    const Image one = run(adaptive(0.1f, 3), 70, 45, colour, &c1, 1);
    const Image three = run(adaptive(0.1f, 3), 70, 45, colour, &c3, 3);
    EXPECT_TRUE(same_bits(one, three));
    EXPECT_EQ(c1.samples, c3.samples);
    EXPECT_EQ(c1.pixels_refined, c3.pixels_refined);
}

TEST(AaMaskImage, ShowsRefinedPixelsInTheirLevelsColourOverADimRender) {
    AaMask mask;
    mask.width = 3;
    mask.height = 1;
    mask.level = {0, 1, 3};
    const Image render(3, 1, Rgb{1.0f});
    const Image img = aa_mask_image(mask, render);
    EXPECT_NEAR(img.at(0, 0).x, 0.25f, 1e-6f);
    EXPECT_NE(img.at(1, 0), img.at(2, 0));
    EXPECT_NE(img.at(1, 0), img.at(0, 0));
}

}  // namespace
}  // namespace luz
