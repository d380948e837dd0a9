// Adaptive antialiasing (docs/SCENES.md#antialiasing): a sample at each pixel corner, pixels whose
// corners differ split into four recursively (refine_tile), and the mask of what was refined
// (--aa-mask); sample_tile_corners() and sample_tile_adaptive() render a tile's two passes with a
// colour function.
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

/// Adaptive sampling (docs/SCENES.md#antialiasing): corner samples shared by neighbouring pixels, a
/// pixel whose corners differ by more than `threshold` split into 4, recursively, up to `max_level`
/// times. Sub-corners lie on the pixel's finest lattice: (i + k/S, j + l/S), S = 2^max_level.
struct AdaptiveSpec {
    float threshold = 0.1f;
    int max_level = 3;
    int width = 0, height = 0;  ///< the image's size

    static AdaptiveSpec from(const AntialiasDesc& aa, int width, int height);
    int lattice() const { return 1 << max_level; }  ///< S
};

/// Largest per-channel difference among four colours, on values clamped to [0, 1].
inline float corner_difference(const Rgb& a, const Rgb& b, const Rgb& c, const Rgb& d) {
    // Plain comparisons (minss/maxss), not fminf/fmaxf calls: this runs for every pixel.
    const auto lo = [](float p, float q) { return q < p ? q : p; };
    const auto hi = [](float p, float q) { return p < q ? q : p; };
    const auto range = [&](float p, float q, float r, float s) {
        const float top = std::min(hi(hi(p, q), hi(r, s)), 1.0f);
        const float bottom = std::max(lo(lo(p, q), lo(r, s)), 0.0f);
        return top > bottom ? top - bottom : 0.0f;
    };
    return hi(hi(range(a.x, b.x, c.x, d.x), range(a.y, b.y, c.y, d.y)), range(a.z, b.z, c.z, d.z));
}

/// The sub-corners a tile's refined pixels have sampled, so that each is sampled once: those
/// on pixel edges are shared with the neighbouring pixel of the same tile; those inside a pixel
/// belong to it. Entries are stamped with a generation instead of being cleared. One per thread
/// and sample type (Rgb, TermSample).
template <class Sample>
class AdaptiveCache {
  public:
    struct Slot {
        Sample colour;
        uint32_t stamp = 0;
    };

    /// Starts a tile: forgets every edge sub-corner.
    void begin_tile(const PixelRect& tile, int S);
    /// Starts pixel (i, j) of the tile: forgets the inner sub-corners.
    void begin_pixel(int i, int j);
    /// The slot of sub-corner (k, l) of the current pixel, 0 ≤ k, l ≤ S, not a pixel corner.
    Slot& slot(int k, int l);
    /// Whether `s` holds a colour sampled for this tile (edge) or pixel (inside).
    bool valid(const Slot& s, int k, int l) const {
        const bool edge = k == 0 || k == S_ || l == 0 || l == S_;
        return s.stamp == (edge ? tile_gen_ : pixel_gen_);
    }
    /// Marks `s` as sampled.
    void fill(Slot& s, int k, int l, const Sample& c) {
        const bool edge = k == 0 || k == S_ || l == 0 || l == S_;
        s.colour = c;
        s.stamp = edge ? tile_gen_ : pixel_gen_;
    }

    /// This thread's cache.
    static AdaptiveCache& for_this_thread();

  private:
    uint32_t next_generation();

    std::vector<Slot> rows_, cols_, inner_;  ///< horizontal edges, vertical edges, inside
    PixelRect tile_;
    int S_ = 1, li_ = 0, lj_ = 0;  ///< lattice, current pixel in the tile
    uint32_t generation_ = 0, tile_gen_ = 0, pixel_gen_ = 0;
};

namespace detail {

/// One pixel's recursive refinement over its sub-corner lattice.
template <class Sample, class Fine>
struct Refiner {
    const AdaptiveSpec& spec;
    AdaptiveCache<Sample>& cache;
    Fine& fine;
    SamplerCounts& counts;
    int i, j, S, deepest = 0;

    Sample at(int k, int l) {
        typename AdaptiveCache<Sample>::Slot& s = cache.slot(k, l);
        if (!cache.valid(s, k, l)) {
            cache.fill(s, k, l, fine.colour(i, j, k, l));
            ++counts.samples;
        }
        return s.colour;
    }

    /// The value of the (sub-)pixel [k, k+size] × [l, l+size] with corners c00 … c11:
    /// the mean of its corners, or split into 4 and the mean of its parts.
    Sample value(int k, int l, int size, int level, const Sample& c00, const Sample& c10,
                 const Sample& c01, const Sample& c11) {
        if (level < spec.max_level &&
            corner_difference(colour_of(c00), colour_of(c10), colour_of(c01), colour_of(c11)) >
                spec.threshold) {
            deepest = std::max(deepest, level + 1);
            const int h = size / 2;
            const Sample cm0 = at(k + h, l), c0m = at(k, l + h), cmm = at(k + h, l + h);
            const Sample c1m = at(k + size, l + h), cm1 = at(k + h, l + size);
            const Sample sum = value(k, l, h, level + 1, c00, cm0, c0m, cmm) +
                               value(k + h, l, h, level + 1, cm0, c10, cmm, c1m) +
                               value(k, l + h, h, level + 1, c0m, cmm, c01, cm1) +
                               value(k + h, l + h, h, level + 1, cmm, c1m, cm1, c11);
            return sum * 0.25f;
        }
        return (c00 + c10 + c01 + c11) * 0.25f;
    }
};

}  // namespace detail

/// Adaptive antialiasing of the pixels of `tile`. `corners` holds the (W+1)×(H+1) samples at
/// the pixel corners (x, y integers), row-major (Rgb colours, or TermSample). `fine` provides
/// the rest:
/// `fine.begin_pixel(i, j)` once before the first sub-corner of a refined pixel and
/// `fine.colour(i, j, k, l)`, the colour at (i + k/S, j + l/S). Writes the pixels into `out`,
/// their levels into `mask` (if any) and counts sub-corner samples and refined pixels.
/// `tick()` is called after each pixel (progress).
template <class Sample, class Fine, class Out, class Tick = void (*)()>
void refine_tile(
    const AdaptiveSpec& spec, const PixelRect& tile, const Sample* corners, Fine& fine, Out& out,
    AaMask* mask, SamplerCounts& counts, Tick&& tick = +[] {}) {
    const int S = spec.lattice();
    const size_t row = static_cast<size_t>(spec.width) + 1;
    AdaptiveCache<Sample>& cache = AdaptiveCache<Sample>::for_this_thread();
    cache.begin_tile(tile, S);
    for (int j = tile.y0; j < tile.y1; ++j) {
        for (int i = tile.x0; i < tile.x1; ++i) {
            const Sample* c = corners + static_cast<size_t>(j) * row + i;
            const Sample &c00 = c[0], &c10 = c[1], &c01 = c[row], &c11 = c[row + 1];
            Sample value;
            int deepest = 0;
            if (spec.max_level > 0 &&
                corner_difference(colour_of(c00), colour_of(c10), colour_of(c01), colour_of(c11)) >
                    spec.threshold) {
                cache.begin_pixel(i, j);
                fine.begin_pixel(i, j);
                detail::Refiner<Sample, Fine> r{spec, cache, fine, counts, i, j, S};
                value = r.value(0, 0, S, 0, c00, c10, c01, c11);
                deepest = r.deepest;
                ++counts.pixels_refined;
            } else {
                value = (c00 + c10 + c01 + c11) * 0.25f;
            }
            put(out, i, j, value);
            if (mask) mask->level[static_cast<size_t>(j) * spec.width + i] = uint8_t(deepest);
            tick();
        }
    }
}

/// The corners (x, y) that tile `tile` computes in the first adaptive pass: those of its
/// pixels' top-left corners, and the image's last column and row for the tiles at its edge.
inline PixelRect corner_rect(const PixelRect& tile, int width, int height) {
    return {tile.x0, tile.y0, tile.x1 + (tile.x1 == width ? 1 : 0),
            tile.y1 + (tile.y1 == height ? 1 : 0)};
}

/// Adaptive's pass 1 for one tile: the samples at the corners `r` (corner_rect()) into
/// `corners` (rows of `row` samples), one point at a time; the corners of `window`'s pixels
/// counted as its pixels. `work` is the tile's counters, counts and progress
/// (render/tile_store.h).
template <class Colour, class Work, class S>
void sample_tile_corners(const PixelRect& r, const PixelRect& window, Colour& colour, Work& work,
                         S* corners, size_t row) {
    for (int y = r.y0; y < r.y1; ++y) {
        for (int x = r.x0; x < r.x1; ++x) {
            const float fx = static_cast<float>(x), fy = static_cast<float>(y);
            work.progress.cost(
                sample_points(colour, &fx, &fy, 1, work.counters, &corners[y * row + x]));
            // the window's pixels: its corners less its last row and column
            if (x < window.x1 && y < window.y1) work.progress.pixel();
        }
    }
    work.counts.samples += static_cast<uint64_t>(r.width()) * r.height();
}

/// Adaptive's pass 2 for one tile: its pixels refined where their `corners` differ
/// (refine_tile()), the sub-corners asked of `colour` one at a time, into `out` and `mask`.
template <class Colour, class Work, class S, class Out>
void sample_tile_adaptive(const AdaptiveSpec& spec, const PixelRect& tile, const S* corners,
                          Colour& colour, Work& work, Out& out, AaMask* mask) {
    struct Fine {
        Colour& fn;
        Work& work;
        float inv_S;
        void begin_pixel(int, int) {}
        S colour(int i, int j, int k, int l) {
            const float x = static_cast<float>(i) + static_cast<float>(k) * inv_S;
            const float y = static_cast<float>(j) + static_cast<float>(l) * inv_S;
            S s;
            work.progress.cost(sample_points(fn, &x, &y, 1, work.counters, &s));
            return s;
        }
    };
    Fine fine{colour, work, 1.0f / static_cast<float>(spec.lattice())};
    refine_tile(spec, tile, corners, fine, out, mask, work.counts,
                [&work] { work.progress.pixel(); });
}

/// An image that shows which pixels adaptive antialiasing refined and how deeply: pixels not
/// refined in dim grey (a quarter of the render's luminance), refined ones in a colour per
/// level: 1 blue, 2 cyan, 3 green, 4 yellow, 5 orange, 6 red.
Image aa_mask_image(const AaMask& mask, const Image& render);

}  // namespace luz
