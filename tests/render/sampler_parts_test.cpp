// The sampler's parts on synthetic colour functions: a colour function's runs() gets a whole
// tile in row order, the cost it reports hands progress over at once, the tile grid's region
// and order, and the tile bytes written and read by one description.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "render/no_aa.h"
#include "render/sampler.h"
#include "same_bits.h"

namespace luz {
namespace {

struct NoCounters {};

Rgb shade_at(float x, float y) { return {x * 0.01f, y * 0.02f, 0.5f}; }

/// A colour function that groups samples itself (runs()), recording what it was asked, and
/// reporting `cost` per sample.
struct Grouping {
    std::vector<std::vector<float>>* calls;
    double cost = 0;
    Rgb operator()(float x, float y, NoCounters&) const { return shade_at(x, y); }
    template <class Done>
    void runs(const float* xs, const float* ys, int n, NoCounters&, Rgb* out, Done&& done) const {
        calls->emplace_back(xs, xs + n);
        for (int k = 0; k < n; ++k) {
            out[k] = shade_at(xs[k], ys[k]);
            done(k + 1, cost);
        }
    }
};

/// A colour function with batch(), reporting `cost` per batch.
struct Batching {
    double cost = 0;
    Rgb operator()(float x, float y, NoCounters&) const { return shade_at(x, y); }
    double batch(const float* xs, const float* ys, int n, NoCounters&, Rgb* out) const {
        for (int k = 0; k < n; ++k) out[k] = shade_at(xs[k], ys[k]);
        return cost;
    }
};

AntialiasDesc mode(AaMode m) {
    AntialiasDesc aa;
    aa.mode = m;
    aa.samples = 4;
    aa.threshold = 0.001f;  // adaptive: every pixel of shade_at() refined
    return aa;
}

template <class Colour>
Image render(const AntialiasDesc& aa, int w, int h, const Colour& colour, int* reports = nullptr) {
    Image out(w, h);
    RenderControl control;
    control.threads = 1;
    if (reports) control.progress = [reports](double) { ++*reports; };
    std::vector<NoCounters> counters;
    sample_image(aa, w, h, control, colour, out, counters, nullptr);
    return out;
}

TEST(ColourFunction, RunsGetEachTileWholeInTileOrder) {
    std::vector<std::vector<float>> calls;
    const Grouping grouping{&calls};
    const auto plain = [](float x, float y, NoCounters&) { return shade_at(x, y); };
    const AntialiasDesc none = mode(AaMode::none);
    EXPECT_TRUE(same_bits(render(none, 20, 18, grouping), render(none, 20, 18, plain)));
    std::vector<size_t> sizes;
    for (const auto& c : calls) sizes.push_back(c.size());
    std::sort(sizes.begin(), sizes.end());
    EXPECT_EQ(sizes, (std::vector<size_t>{8, 32, 64, 256}));  // 4×2, 16×2, 4×16, 16×16
    // a whole tile's x: 8 × 8 blocks of 4 × 2 packets (x 0…3 twice, then 4…7 twice, …)
    int dx[256], dy[256];
    ASSERT_EQ(tile_order(16, 16, dx, dy), 256);
    for (const auto& c : calls) {
        if (c.size() != 256) continue;
        for (int k = 0; k < 256; ++k) EXPECT_EQ(c[k], static_cast<float>(dx[k]) + 0.5f);
        for (int k = 0; k < 8; ++k) EXPECT_EQ(c[k], static_cast<float>(k % 4) + 0.5f);
        EXPECT_EQ(c[8], 4.5f);
    }
}

TEST(ColourFunction, TileOrderHasEveryPixelOnceInPacketsOfFourByTwo) {
    for (const auto& [w, h] : {std::pair{16, 16}, {5, 16}, {16, 3}, {1, 1}, {9, 7}}) {
        int dx[256], dy[256];
        const int n = tile_order(w, h, dx, dy);
        ASSERT_EQ(n, w * h);
        std::vector<int> seen(static_cast<size_t>(w * h), 0);
        for (int k = 0; k < n; ++k) {
            ASSERT_TRUE(dx[k] >= 0 && dx[k] < w && dy[k] >= 0 && dy[k] < h) << w << "x" << h;
            ++seen[static_cast<size_t>(dy[k] * w + dx[k])];
        }
        EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), n) << w << "x" << h;
    }
    int dx[256], dy[256];
    tile_order(16, 16, dx, dy);
    for (int k = 0; k < 256; k += 8) {  // each packet of eight: a 4 × 2 rectangle
        const int x0 = *std::min_element(dx + k, dx + k + 8),
                  y0 = *std::min_element(dy + k, dy + k + 8);
        for (int j = 0; j < 8; ++j) {
            EXPECT_EQ(dx[k + j], x0 + j % 4);
            EXPECT_EQ(dy[k + j], y0 + j / 4);
        }
    }
}

TEST(ColourFunction, CostlySamplesHandProgressOverAtOnce) {
    // One 16×16 tile: without cost, progress is handed over once a pass; with a cost of 1 a
    // sample (a report's worth), after every pixel.
    std::vector<std::vector<float>> calls;
    int cheap = 0, costly = 0;
    const AntialiasDesc none = mode(AaMode::none);
    render(none, 16, 16, Grouping{&calls, 0.0}, &cheap);
    render(none, 16, 16, Grouping{&calls, 1.0}, &costly);
    EXPECT_EQ(cheap, 1);
    EXPECT_EQ(costly, 256);
    for (AaMode m : {AaMode::grid, AaMode::adaptive}) {
        int few = 0, many = 0;
        const int passes = m == AaMode::adaptive ? 2 : 1;
        render(mode(m), 16, 16, Batching{0.0}, &few);
        render(mode(m), 16, 16, Batching{1.0}, &many);
        EXPECT_EQ(few, passes);
        EXPECT_EQ(many, 256 * passes);
    }
}

TEST(TileGrid, ARegionsTilesInRenderOrderCutToIt) {
    const TileGrid tiles(40, 20, PixelRect{10, 5, 20, 18});
    EXPECT_EQ(tiles.count, 6u);  // 3 × 2 tiles, the last column and row cut by the image
    EXPECT_EQ(tiles.tile(5).x1, 40);
    EXPECT_EQ(tiles.tile(5).y1, 20);
    const std::vector<size_t> list = tiles.within(tiles.window);
    std::vector<size_t> expected;
    for (size_t t : tile_order(6))
        if (t == 0 || t == 1 || t == 3 || t == 4) expected.push_back(t);
    EXPECT_EQ(list, expected);
    EXPECT_EQ(tiles.pixels(0), 6u * 11u);  // x 10..15, y 5..15
    EXPECT_EQ(tiles.pixels(4), 4u * 2u);   // x 16..19, y 16..17
    EXPECT_EQ(tiles.pixels(2), 0u);
}

TEST(TileBytes, OneDescriptionWritesAndReadsTheSameBytes) {
    std::vector<float> plane(6 * 4);
    for (size_t k = 0; k < plane.size(); ++k) plane[k] = static_cast<float>(k) * 1.5f;
    const PixelRect r{1, 1, 4, 3};
    uint64_t count = 7;
    const auto describe = [&](auto& io) {
        io.raw(count);
        io.plane(plane.data(), 6, r);
    };
    std::string bytes;
    TileWriter w{bytes};
    describe(w);
    std::string expected;  // as the values one by one, row by row
    append_raw(expected, count);
    for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x) append_raw(expected, plane[y * 6 + x]);
    EXPECT_EQ(bytes, expected);
    const std::vector<float> saved = plane;
    std::fill(plane.begin(), plane.end(), 0.0f);
    count = 0;
    std::string_view in = bytes;
    TileReader rd{in};
    describe(rd);
    EXPECT_TRUE(in.empty());
    EXPECT_EQ(count, 7u);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 6; ++x) {
            const bool inside = x >= r.x0 && x < r.x1 && y >= r.y0 && y < r.y1;
            EXPECT_EQ(plane[y * 6 + x], inside ? saved[y * 6 + x] : 0.0f);
        }
    std::string_view shorter = std::string_view(bytes).substr(0, bytes.size() - 1);
    TileReader cut{shorter};
    EXPECT_THROW(describe(cut), InputError);
}

}  // namespace
}  // namespace luz
