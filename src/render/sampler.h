// Antialiasing of docs/SCENES.md#antialiasing — none, grid (box or tent filter, optional jitter)
// and adaptive — independent of how a colour is computed: the samplers ask for "the colour at
// pixel-space point (x, y)" and combine the answers. The ray pipelines use sample_image(); the
// zbuffer uses the same positions, filter (filter_tile) and refinement (refine_tile) with its own
// rasterizer.
#pragma once
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <utility>
#include <vector>

#include "image/image.h"
#include "render/adaptive_aa.h"
#include "render/aov.h"
#include "render/checkpoint.h"
#include "render/grid_aa.h"
#include "render/parallel.h"
#include "render/render.h"
#include "render/tile_bytes.h"
#include "render/tiles.h"
#include "render/work_items.h"
#include "scene/input_error.h"
#include "scene/scene_desc.h"

namespace luz {

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

}  // namespace luz
