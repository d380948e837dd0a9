// Antialiasing of SPEC §1.2 — none, grid (box or tent filter, optional jitter) and adaptive —
// independent of how a colour is computed: the samplers ask for "the colour at pixel-space point
// (x, y)" and combine the answers. The ray pipelines use sample_image(); the zbuffer uses the
// same positions, filter (filter_tile) and refinement (refine_tile) with its own rasterizer.
#pragma once

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "image/image.h"
#include "render/aov.h"
#include "render/checkpoint.h"
#include "render/parallel.h"
#include "render/render.h"
#include "render/work_items.h"
#include "scene/input_error.h"
#include "scene/scene_desc.h"

namespace luz {

/// Which pixels adaptive antialiasing refined and how deeply (`--aa-mask`).
struct AaMask {
    int width = 0, height = 0;
    std::vector<uint8_t> level;  ///< per pixel, row-major: times split (0: not refined)
};

/// What a sampler counted in one work item; items are summed in order.
struct SamplerCounts {
    uint64_t samples = 0;         ///< colour evaluations
    uint64_t pixels_refined = 0;  ///< adaptive: pixels split at least once

    void add(const SamplerCounts& o) {
        samples += o.samples;
        pixels_refined += o.pixels_refined;
    }
};

/// Side of the square tiles the samplers work in (pixels).
inline constexpr int kSamplerTile = 16;
/// Samples of a tile taken together (sample_points()) when a tile has no antialiasing, in row
/// order (four rows of a whole tile): the batch whose ray trees the ray tracer traces side by
/// side (BatchTracer::samples()). Progress moves by these runs.
inline constexpr int kSamplerRun = 64;
/// The work (work_of(): rays, for the ray tracer) a pixel's samples take on average above which
/// the pixels after them are taken one at a time, so that progress moves pixel by pixel even
/// when one pixel takes seconds (an exploding ray tree); a tile's first pixel is taken alone to
/// find out.
inline constexpr uint64_t kHeavyPixelWork = 4096;

/// The work a work item's counters have counted so far (rays, for the ray tracer's counters:
/// render/whitted.h overloads it); progress is reported sooner after costly pixels.
template <class Counters>
uint64_t work_of(const Counters&) {
    return 0;
}

/// The primary rays a work item's counters have counted (render/whitted.h overloads it): how a
/// render shared among processes reports each one's share (SPEC §3.1).
template <class Counters>
uint64_t primary_rays_of(const Counters&) {
    return 0;
}

/// Progress by pixels finished (not only by tiles), reported to RenderControl::progress: each
/// work item calls pixel() after every pixel; a count is handed over at the end of every
/// kFlushPixels pixels (a tile's worth), or at once after a pixel whose work (rays) was large,
/// so that the bar moves even when single pixels take seconds. The shared count is touched
/// rarely: an atomic add every 16 pixels, its cache line passed between the cores, was 4 % of a
/// 3200×2400 Whitted render on two cores. With tiles rendered in a scattered order
/// (tile_order()), the share of pixels done is an unbiased estimate of the share of work.
class PixelProgress {
  public:
    PixelProgress(const RenderControl& control, uint64_t total_pixels)
        : control_(control), total_(total_pixels ? total_pixels : 1) {}

    /// One work item's reports: a local count, handed over now and then.
    template <class Counters>
    struct Item {
        PixelProgress& p;
        const Counters& counters;
        uint64_t pending = 0, work_at_flush = 0;

        void pixel() {
            ++pending;
            const uint64_t work = work_of(counters);
            if (pending >= kFlushPixels || work - work_at_flush >= kFlushWork) {
                p.add(pending);
                pending = 0;
                work_at_flush = work;
            }
        }
        ~Item() {
            if (pending) p.add(pending);
        }
    };

    void add(uint64_t pixels) {
        const uint64_t done = done_.fetch_add(pixels, std::memory_order_relaxed) + pixels;
        if (control_.progress) control_.progress(static_cast<double>(done) / total_);
    }

  private:
    static constexpr uint64_t kFlushPixels = kSamplerTile * kSamplerTile;  ///< pixels, at most
    static constexpr uint64_t kFlushWork = 2048;  ///< rays after which a count is handed over
    const RenderControl& control_;
    uint64_t total_;
    alignas(64) std::atomic<uint64_t> done_{0};  ///< on a cache line of its own
};

/// The pixels a render computes: RenderControl::region (inside the image), or the whole image.
inline PixelRect render_window(const RenderControl& control, int width, int height) {
    const PixelRect whole{0, 0, width, height};
    return control.region.empty() ? whole : control.region.clipped(whole);
}

/// The pixels whose top-left corners adaptive's pass 1 computes for the pixels of `window`:
/// `window` grown by one pixel to the right and below (inside the image), for the corners of
/// its last column and row.
inline PixelRect corner_window(const PixelRect& window, int width, int height) {
    return {window.x0, window.y0, std::min(width, window.x1 + 1), std::min(height, window.y1 + 1)};
}

/// The order in which tiles are rendered: a fixed pseudo-random permutation of 0 … count−1
/// (the same in every run), so that costly regions are spread over the whole render and the
/// progress bar's time left stays honest. The image does not depend on the order.
std::vector<size_t> tile_order(size_t count);

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

/// Tent weight of a sample (dx, dy) pixels from a pixel's centre (SPEC §1.2).
inline float tent_weight(float dx, float dy) { return tent1(dx) * tent1(dy); }

/// Grid sampling (SPEC §1.2): s² samples per pixel, sample (a, b) of pixel (i, j) at
/// (i + (a+0.5)/s, j + (b+0.5)/s), or with jitter uniformly inside its cell.
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

/// Adaptive sampling (SPEC §1.2): corner samples shared by neighbouring pixels, a pixel whose
/// corners differ by more than `threshold` split into 4, recursively, up to `max_level` times.
/// Sub-corners lie on the pixel's finest lattice: (i + k/S, j + l/S), S = 2^max_level.
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

/// Per-thread working memory of grid sampling: one tile's samples (Rgb or TermSample).
template <class S>
std::vector<S>& grid_scratch_for_this_thread() {
    thread_local std::vector<S> buf;
    return buf;
}

/// Checkpoint bytes of a work item (render/checkpoint.h): raw copies of plain values and of
/// the output's pixels in a rectangle, read back in the same order.
template <class T>
void append_raw(std::string& out, const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    out.append(reinterpret_cast<const char*>(&v), sizeof v);
}
template <class T>
void read_raw(std::string_view& in, T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    if (in.size() < sizeof v)
        throw InputError("--checkpoint: damaged checkpoint (a tile is short)");
    std::memcpy(&v, in.data(), sizeof v);
    in.remove_prefix(sizeof v);
}
/// The pixels of `r` of an image, or of the image and each term plane of a TermOut.
void append_rect(std::string& out, const Image& img, const PixelRect& r);
void read_rect(std::string_view& in, Image& img, const PixelRect& r);
void append_rect(std::string& out, const TermOut& o, const PixelRect& r);
void read_rect(std::string_view& in, TermOut& o, const PixelRect& r);
void append_rect(std::string& out, const ImageRows& o, const PixelRect& r);
void read_rect(std::string_view& in, ImageRows& o, const PixelRect& r);

/// The samples at (xs[k], ys[k]) for k < n into out[k]: by colour.batch() when the colour has
/// one (the ray tracer's, which traces neighbouring camera rays as packets), else one by one.
template <class Colour, class Counters, class S>
void sample_points(Colour& colour, const float* xs, const float* ys, int n, Counters& c, S* out) {
    if constexpr (requires { colour.batch(xs, ys, n, c, out); }) {
        colour.batch(xs, ys, n, c, out);
    } else {
        for (int k = 0; k < n; ++k) out[k] = colour(xs[k], ys[k], c);
    }
}

/// Renders an image with the antialiasing `aa`: `colour(x, y, counters)` gives the sample at
/// pixel-space point (x, y) — an Rgb colour, or a TermSample (its colour and terms), put into
/// `out` (an Image, or a TermOut) — and may count into `counters` (one Counters per work item, in
/// `counters`, to be summed by the caller; each item counts into a local copy first, so that
/// threads never write to one cache line). Square tiles are rendered in parallel; the result
/// does not depend on the thread count. Fills `mask` (if any); returns the counts.
template <class Counters, class Colour, class Out>
SamplerCounts sample_image(const AntialiasDesc& aa, int width, int height,
                           const RenderControl& control, Colour&& colour, Out& out,
                           std::vector<Counters>& counters, AaMask* mask) {
    using S = std::decay_t<decltype(colour(0.0f, 0.0f, std::declval<Counters&>()))>;
    const int T = kSamplerTile;
    const int tiles_x = (width + T - 1) / T, tiles_y = (height + T - 1) / T;
    const size_t tile_count = static_cast<size_t>(tiles_x) * tiles_y;
    const bool adaptive = aa.mode == AaMode::adaptive;
    const size_t items = adaptive ? 2 * tile_count : tile_count;  // adaptive: two passes
    counters.assign(items, Counters{});
    std::vector<SamplerCounts> counts(items);
    if (mask) {
        mask->width = width;
        mask->height = height;
        mask->level.assign(static_cast<size_t>(width) * height, 0);
    }
    // Tiles in a scattered order (tile_order); counters are kept per tile, summed in tile order.
    const std::vector<size_t> order = tile_order(tile_count);
    auto tile_of = [&](size_t t) {
        const int x0 = static_cast<int>(t % tiles_x) * T, y0 = static_cast<int>(t / tiles_x) * T;
        return PixelRect{x0, y0, std::min(width, x0 + T), std::min(height, y0 + T)};
    };
    // --region: only the tiles that hold its pixels, each cut to it. A pixel's value does not
    // depend on its tile (its samples, the tent's ring and its corners are computed where
    // needed, at the same points), so the region's pixels are those of the whole render.
    const PixelRect window = render_window(control, width, height);
    auto tiles_within = [&](const PixelRect& within) {
        std::vector<size_t> list;
        for (size_t t : order)
            if (tile_of(t).overlaps(within)) list.push_back(t);
        return list;
    };
    const std::vector<size_t> tiles = tiles_within(window);
    auto pixels_of = [&](size_t t) {
        const PixelRect r = tile_of(t).clipped(window);
        return r.empty() ? uint64_t{0} : static_cast<uint64_t>(r.width()) * r.height();
    };
    // Progress by pixels: adaptive counts each pixel in both passes.
    PixelProgress progress(
        control, static_cast<uint64_t>(window.width()) * window.height() * (adaptive ? 2 : 1));
    // Each pass: the tiles' bytes are their counters and pixels (checkpoint and MPI).
    Checkpoint* const checkpoint = control.checkpoint;
    if (checkpoint) checkpoint->start(items);
    const auto elsewhere = [&](size_t t) { progress.add(pixels_of(t)); };
    // The bytes of a tile of pixels (none, grid): its counters, then its pixels.
    const auto write_pixels = [&](size_t t, std::string& o) {
        append_raw(o, counters[t]);
        append_raw(o, counts[t]);
        append_rect(o, out, tile_of(t).clipped(window));
    };
    const auto read_pixels = [&](size_t t, std::string_view& in) {
        read_raw(in, counters[t]);
        read_raw(in, counts[t]);
        read_rect(in, out, tile_of(t).clipped(window));
    };
    const auto rays_of = [&](size_t t) { return primary_rays_of(counters[t]); };

    switch (aa.mode) {
        case AaMode::none: {
            auto code = TileCode{
                [&](size_t t) {
                    const PixelRect r = tile_of(t).clipped(window);
                    Counters c{};
                    {
                        PixelProgress::Item<Counters> tick{progress, c};
                        // kSamplerRun pixel centres at a time, row by row
                        // (the ray tracer's ray trees fill its lanes level
                        // by level), then their progress; heavy pixels one
                        // at a time (kHeavyPixelWork), the tile's first too
                        const int w = r.width(), n = w * r.height();
                        float xs[kSamplerRun], ys[kSamplerRun];
                        S run[kSamplerRun];
                        for (int first = 0, size = 1, m; first < n; first += m) {
                            m = std::min(size, n - first);
                            const uint64_t work = work_of(c);
                            for (int k = 0; k < m; ++k) {
                                xs[k] = (r.x0 + (first + k) % w) + 0.5f;
                                ys[k] = (r.y0 + (first + k) / w) + 0.5f;
                            }
                            sample_points(colour, xs, ys, m, c, run);
                            for (int k = 0; k < m; ++k) {
                                put(out, r.x0 + (first + k) % w, r.y0 + (first + k) / w, run[k]);
                                tick.pixel();
                            }
                            const bool heavy = work_of(c) - work >= kHeavyPixelWork * m;
                            size = heavy ? 1 : kSamplerRun;
                        }
                    }
                    counters[t] = c;
                    counts[t].samples = static_cast<uint64_t>(r.width()) * r.height();
                },
                write_pixels, read_pixels};
            run_pass(control, checkpoint, tiles, 0, false, code, elsewhere, rays_of);
            break;
        }
        case AaMode::grid: {
            const GridSpec g = GridSpec::from(aa, width, height);
            auto code = TileCode{
                [&](size_t t) {
                    const PixelRect tile = tile_of(t).clipped(window), region = g.region(tile);
                    const int s = g.s, stride = region.width() * s;
                    std::vector<S>& buf = grid_scratch_for_this_thread<S>();
                    Counters c{};
                    PixelProgress::Item<Counters> tick{progress, c};
                    buf.resize(static_cast<size_t>(stride) * region.height() * s);
                    for (int j = region.y0; j < region.y1; ++j) {
                        for (int i = region.x0; i < region.x1; ++i) {
                            const bool inside =
                                i >= tile.x0 && i < tile.x1 && j >= tile.y0 && j < tile.y1;
                            // the pixel's needed samples at once, in chunks
                            constexpr int kChunk = 64;
                            float xs[kChunk], ys[kChunk];
                            S* dst[kChunk];
                            S got[kChunk];
                            int n = 0;
                            const auto flush = [&] {
                                sample_points(colour, xs, ys, n, c, got);
                                for (int k = 0; k < n; ++k) *dst[k] = got[k];
                                counts[t].samples += static_cast<uint64_t>(n);
                                n = 0;
                            };
                            for (int b = 0; b < s; ++b) {
                                S* row =
                                    &buf[static_cast<size_t>((j - region.y0) * s + b) * stride +
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
                            if (inside) tick.pixel();
                        }
                    }
                    counters[t] = c;
                    filter_tile(g, tile, region, buf.data(), out);
                },
                write_pixels, read_pixels};
            run_pass(control, checkpoint, tiles, 0, false, code, elsewhere, rays_of);
            break;
        }
        case AaMode::adaptive: {
            // Pass 1: one sample at every pixel corner, each computed once.
            // A region's pixels need the corners [x0, x1] × [y0, y1]: the tiles of the region
            // grown by one pixel to the right and below compute them. Every process needs
            // them all for pass 2.
            std::vector<S> corners(static_cast<size_t>(width + 1) * (height + 1));
            const PixelRect grown = corner_window(window, width, height);
            const std::vector<size_t> corner_tiles = tiles_within(grown);
            const auto corners_of = [&](size_t t) {
                return corner_rect(tile_of(t).clipped(grown), width, height);
            };
            const auto corner_row = [&](const PixelRect& r, int y) {
                return corners.data() + static_cast<size_t>(y) * (width + 1) + r.x0;
            };
            auto pass1 =
                TileCode{[&](size_t t) {
                             const PixelRect r = corners_of(t);
                             Counters c{};
                             {
                                 PixelProgress::Item<Counters> tick{progress, c};
                                 for (int y = r.y0; y < r.y1; ++y) {
                                     for (int x = r.x0; x < r.x1; ++x) {
                                         corners[static_cast<size_t>(y) * (width + 1) + x] = colour(
                                             static_cast<float>(x), static_cast<float>(y), c);
                                         // the region's pixels: its corners less its last row and
                                         // column
                                         if (x < window.x1 && y < window.y1) tick.pixel();
                                     }
                                 }
                             }
                             counters[t] = c;
                             counts[t].samples = static_cast<uint64_t>(r.width()) * r.height();
                         },
                         [&](size_t t, std::string& o) {
                             const PixelRect r = corners_of(t);
                             append_raw(o, counters[t]);
                             append_raw(o, counts[t]);
                             for (int y = r.y0; y < r.y1; ++y)
                                 for (int x = 0; x < r.width(); ++x)
                                     append_raw(o, corner_row(r, y)[x]);
                         },
                         [&](size_t t, std::string_view& in) {
                             const PixelRect r = corners_of(t);
                             read_raw(in, counters[t]);
                             read_raw(in, counts[t]);
                             for (int y = r.y0; y < r.y1; ++y)
                                 for (int x = 0; x < r.width(); ++x)
                                     read_raw(in, corner_row(r, y)[x]);
                         }};
            run_pass(control, checkpoint, corner_tiles, 0, true, pass1, elsewhere, rays_of);
            // Pass 2: refine the pixels whose corners differ (item tile_count + t).
            const AdaptiveSpec spec = AdaptiveSpec::from(aa, width, height);
            const float inv_S = 1.0f / static_cast<float>(spec.lattice());
            const auto mask_levels = [&](size_t t, auto&& each) {  // the mask's bytes of a tile
                if (!mask) return;
                const PixelRect r = tile_of(t).clipped(window);
                for (int y = r.y0; y < r.y1; ++y)
                    for (int x = r.x0; x < r.x1; ++x)
                        each(mask->level[static_cast<size_t>(y) * width + x]);
            };
            auto pass2 = TileCode{
                [&](size_t t) {
                    const size_t k = tile_count + t;
                    const PixelRect r = tile_of(t).clipped(window);
                    Counters c{};
                    struct Fine {
                        Colour& fn;
                        Counters& c;
                        float inv_S;
                        void begin_pixel(int, int) {}
                        S colour(int i, int j, int k, int l) {
                            return fn(static_cast<float>(i) + static_cast<float>(k) * inv_S,
                                      static_cast<float>(j) + static_cast<float>(l) * inv_S, c);
                        }
                    };
                    Fine fine{colour, c, inv_S};
                    {
                        PixelProgress::Item<Counters> tick{progress, c};
                        refine_tile(spec, r, corners.data(), fine, out, mask, counts[k],
                                    [&tick] { tick.pixel(); });
                    }
                    counters[k] = c;
                },
                [&](size_t t, std::string& o) {
                    const size_t k = tile_count + t;
                    append_raw(o, counters[k]);
                    append_raw(o, counts[k]);
                    append_rect(o, out, tile_of(t).clipped(window));
                    mask_levels(t, [&](uint8_t& v) { append_raw(o, v); });
                },
                [&](size_t t, std::string_view& in) {
                    const size_t k = tile_count + t;
                    read_raw(in, counters[k]);
                    read_raw(in, counts[k]);
                    read_rect(in, out, tile_of(t).clipped(window));
                    mask_levels(t, [&](uint8_t& v) { read_raw(in, v); });
                }};
            run_pass(control, checkpoint, tiles, tile_count, false, pass2, elsewhere,
                     [&](size_t t) { return primary_rays_of(counters[tile_count + t]); });
            break;
        }
    }
    SamplerCounts total;
    for (const SamplerCounts& c : counts) total.add(c);
    return total;
}

/// An image that shows which pixels adaptive antialiasing refined and how deeply: pixels not
/// refined in dim grey (a quarter of the render's luminance), refined ones in a colour per
/// level: 1 blue, 2 cyan, 3 green, 4 yellow, 5 orange, 6 red.
Image aa_mask_image(const AaMask& mask, const Image& render);

}  // namespace luz
