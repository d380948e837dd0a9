// Antialiasing of docs/SCENES.md#antialiasing — none, grid (box or tent filter, optional jitter)
// and adaptive — independent of how a colour is computed: sample_image() renders an image tile
// by tile with a colour function (render/colour_function.h). The zbuffer uses the same
// positions, filter (filter_tile) and refinement (refine_tile) with its own rasterizer.
#pragma once

#include <cstdint>
#include <vector>

#include "image/image.h"
#include "render/adaptive_aa.h"
#include "render/aov.h"
#include "render/colour_function.h"
#include "render/grid_aa.h"
#include "render/no_aa.h"
#include "render/render.h"
#include "render/tile_store.h"
#include "render/tiles.h"
#include "scene/scene_desc.h"

namespace luz {

/// Renders an image with the antialiasing `aa`: `colour(x, y, counters)` gives the sample at
/// pixel-space point (x, y) — an Rgb colour, or a TermSample (its colour and terms), put into
/// `out` (an Image, or a TermOut) — and may count into `counters` (one Counters per work item,
/// in `counters`, to be summed by the caller). Each tile of the render's window is rendered
/// by the mode's function of (tile, colour function, its work item), in parallel, through the
/// tile store (checkpoint, MPI); the result does not depend on the thread count. Fills `mask`
/// (if any); returns the counts.
template <class Counters, class Colour, class Out>
SamplerCounts sample_image(const AntialiasDesc& aa, int width, int height,
                           const RenderControl& control, Colour&& colour, Out& out,
                           std::vector<Counters>& counters, AaMask* mask) {
    const TileGrid tiles(width, height, render_window(control, width, height));
    const std::vector<size_t> list = tiles.within(tiles.window);
    const bool adaptive = aa.mode == AaMode::adaptive;
    TileStore<Counters> store(control, tiles, adaptive ? 2 : 1, counters);
    if (mask) *mask = AaMask{width, height, std::vector<uint8_t>(size_t(width) * height, 0)};
    const auto pixels = [&](size_t t, auto& io) { io.rect(out, tiles.rect(t)); };
    if (aa.mode == AaMode::none) {
        store.pass(
            0, list, false,
            [&](size_t t, auto& work) { sample_tile_none(tiles.rect(t), colour, work, out); },
            pixels);
    } else if (aa.mode == AaMode::grid) {
        const GridSpec g = GridSpec::from(aa, width, height);
        store.pass(
            0, list, false,
            [&](size_t t, auto& work) { sample_tile_grid(g, tiles.rect(t), colour, work, out); },
            pixels);
    } else {
        // Pass 1: a sample at every pixel corner the window's pixels need (those of the tiles
        // of the window grown by one pixel right and below), each once; every process needs
        // them all for pass 2.
        std::vector<SampleOf<Colour, Counters>> corners(size_t(width + 1) * (height + 1));
        const PixelRect grown = corner_window(tiles.window, width, height);
        const auto corners_of = [&](size_t t) {
            return corner_rect(tiles.tile(t).clipped(grown), width, height);
        };
        store.pass(
            0, tiles.within(grown), true,
            [&](size_t t, auto& work) {
                sample_tile_corners(corners_of(t), tiles.window, colour, work, corners.data(),
                                    size_t(width) + 1);
            },
            [&](size_t t, auto& io) {
                io.plane(corners.data(), size_t(width) + 1, corners_of(t));
            });
        // Pass 2: the pixels whose corners differ, refined.
        const AdaptiveSpec spec = AdaptiveSpec::from(aa, width, height);
        store.pass(
            1, list, false,
            [&](size_t t, auto& work) {
                sample_tile_adaptive(spec, tiles.rect(t), corners.data(), colour, work, out, mask);
            },
            [&](size_t t, auto& io) {
                pixels(t, io);
                if (mask) io.plane(mask->level.data(), size_t(width), tiles.rect(t));
            });
    }
    return store.total();
}

}  // namespace luz
