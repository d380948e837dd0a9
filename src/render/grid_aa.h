// Grid antialiasing (docs/SCENES.md#antialiasing): s² samples a pixel at fixed or jittered
// positions, combined by the box or the tent filter (filter_tile); sample_tile_grid() renders a
// tile of them with a colour function.
#pragma once

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <vector>

#include "image/image.h"
#include "render/aov.h"
#include "render/colour_function.h"
#include "render/tiles.h"
#include "scene/scene_desc.h"

namespace luz {

/// Seed of the jitter hash: a constant, so that every render of a scene is the same.
inline constexpr uint64_t kJitterSeed = 0x6c757a2d6a697474ull;  // "luz-jitt"

/// SplitMix64's finaliser: a bijective mix of 64 bits.
inline uint64_t mix64(uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

/// Jitter offset in [0, 1) of sample `k` of pixel `pixel` (row-major index) along `axis`
/// (0: x, 1: y): a hash of the three, never a shared random generator, so it does not depend
/// on the order in which pixels are rendered.
inline float jitter_offset(uint64_t pixel, uint32_t k, uint32_t axis) {
    const uint64_t h = mix64(mix64(kJitterSeed ^ pixel) + (uint64_t{k} << 1 | axis));
    return static_cast<float>(h >> 40) * 0x1p-24f;  // 24 bits: exact, < 1
}

/// Tent weight of one axis: max(0, 1 − |d|), d in pixels from the pixel's centre.
inline float tent1(float d) { return std::max(0.0f, 1.0f - std::fabs(d)); }

/// Tent weight of a sample (dx, dy) pixels from a pixel's centre (docs/SCENES.md#antialiasing).
inline float tent_weight(float dx, float dy) { return tent1(dx) * tent1(dy); }

/// Grid sampling (docs/SCENES.md#antialiasing): s² samples per pixel, sample (a, b) of pixel (i, j)
/// at (i + (a+0.5)/s, j + (b+0.5)/s), or with jitter uniformly inside its cell.
struct GridSpec {
    int s = 1;
    AaFilter filter = AaFilter::box;
    bool jitter = false;
    int width = 0, height = 0;  ///< the image's size

    static GridSpec from(const AntialiasDesc& aa, int width, int height);

    /// Position of sample (a, b) of pixel (i, j), in pixel coordinates.
    void position(int i, int j, int a, int b, float& x, float& y) const {
        float u = 0.5f, v = 0.5f;
        if (jitter) {
            const uint64_t pixel = static_cast<uint64_t>(j) * static_cast<uint64_t>(width) + i;
            const auto k = static_cast<uint32_t>(b * s + a);
            u = jitter_offset(pixel, k, 0);
            v = jitter_offset(pixel, k, 1);
        }
        const float inv_s = 1.0f / static_cast<float>(s);
        x = static_cast<float>(i) + (static_cast<float>(a) + u) * inv_s;
        y = static_cast<float>(j) + (static_cast<float>(b) + v) * inv_s;
    }

    /// The pixels whose samples the pixels of `tile` need: the tile itself (box), or the tile
    /// and a ring of one pixel around it, inside the image (tent).
    PixelRect region(const PixelRect& tile) const;

    /// Whether a sample at (x, y) weighs anything for some pixel of `tile` (always, for box and
    /// inside the tile); samples of the tent's ring that weigh nothing need not be computed.
    bool needed(const PixelRect& tile, float x, float y) const;
};

/// Combines the samples of the pixels of `region` into the pixels of `tile` of `out` with the
/// grid's filter. `samples` holds (region.width()·s) × (region.height()·s) samples, row-major:
/// sample (a, b) of pixel (i, j) at column (i − region.x0)·s + a, row (j − region.y0)·s + b.
/// Samples that are not needed() are never read with a non-zero weight. A sample is an Rgb
/// colour (Out: Image) or a colour with its terms (TermSample, Out: TermOut), filtered with the
/// same weights (sampler.cpp instantiates both).
template <class S, class Out>
void filter_tile(const GridSpec& g, const PixelRect& tile, const PixelRect& region,
                 const S* samples, Out& out);

/// Per-thread working memory of grid sampling: one tile's samples (Rgb or TermSample).
template <class S>
std::vector<S>& grid_scratch_for_this_thread() {
    thread_local std::vector<S> buf;
    return buf;
}

/// The pixels of `tile` with grid antialiasing, into `out`: the samples of its pixels and of
/// the tent's ring that weigh anything (GridSpec::needed()), asked of `colour` a pixel at a time
/// (sample_points(), in chunks of 64), then filtered (filter_tile()). `work` is the tile's
/// counters, counts and progress (render/tile_store.h).
template <class Colour, class Work, class Out>
void sample_tile_grid(const GridSpec& g, const PixelRect& tile, Colour& colour, Work& work,
                      Out& out) {
    using S = SampleOf<Colour, decltype(work.counters)>;
    const PixelRect region = g.region(tile);
    const int s = g.s, stride = region.width() * s;
    std::vector<S>& buf = grid_scratch_for_this_thread<S>();
    buf.resize(static_cast<size_t>(stride) * region.height() * s);
    for (int j = region.y0; j < region.y1; ++j) {
        for (int i = region.x0; i < region.x1; ++i) {
            const bool inside = i >= tile.x0 && i < tile.x1 && j >= tile.y0 && j < tile.y1;
            constexpr int kChunk = 64;
            float xs[kChunk], ys[kChunk];
            S* dst[kChunk];
            S got[kChunk];
            int n = 0;
            const auto flush = [&] {
                work.progress.cost(sample_points(colour, xs, ys, n, work.counters, got));
                for (int k = 0; k < n; ++k) *dst[k] = got[k];
                work.counts.samples += static_cast<uint64_t>(n);
                n = 0;
            };
            for (int b = 0; b < s; ++b) {
                S* row = &buf[static_cast<size_t>((j - region.y0) * s + b) * stride +
                              (i - region.x0) * s];
                for (int a = 0; a < s; ++a) {
                    float x, y;
                    g.position(i, j, a, b, x, y);
                    if (inside || g.needed(tile, x, y)) {
                        xs[n] = x;
                        ys[n] = y;
                        dst[n++] = &row[a];
                        if (n == kChunk) flush();
                    } else {
                        row[a] = S{};
                    }
                }
            }
            if (n > 0) flush();
            if (inside) work.progress.pixel();
        }
    }
    filter_tile(g, tile, region, buf.data(), out);
}

}  // namespace luz
