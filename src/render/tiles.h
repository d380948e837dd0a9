// The tiles the samplers work in: their size, their rectangles, their order, the region a render
// computes, and what a tile counted.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "render/render.h"

namespace luz {

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

/// The order in which tiles are rendered: a fixed pseudo-random permutation of 0 … count−1
/// (the same in every run), so that costly regions are spread over the whole render and the
/// progress bar's time left stays honest. The image does not depend on the order.
std::vector<size_t> tile_order(size_t count);

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

/// An image cut into kSamplerTile-square tiles, numbered row by row, and the window (region)
/// whose pixels a render computes. A pixel's value does not depend on its tile (its samples,
/// the tent's ring and its corners are computed where needed, at the same points), so the
/// window's pixels are those of the whole render.
struct TileGrid {
    int width, height;
    PixelRect window;
    int across;    ///< tiles in a row
    size_t count;  ///< tiles in the image
    std::vector<size_t> order = tile_order(count);

    TileGrid(int w, int h, const PixelRect& region)
        : width(w),
          height(h),
          window(region),
          across((w + kSamplerTile - 1) / kSamplerTile),
          count(static_cast<size_t>(across) * ((h + kSamplerTile - 1) / kSamplerTile)) {}

    /// Tile t's pixels in the image.
    PixelRect tile(size_t t) const {
        const int x0 = static_cast<int>(t % across) * kSamplerTile;
        const int y0 = static_cast<int>(t / across) * kSamplerTile;
        return {x0, y0, std::min(width, x0 + kSamplerTile), std::min(height, y0 + kSamplerTile)};
    }
    /// Tile t's pixels in the window: the pixels it renders.
    PixelRect rect(size_t t) const { return tile(t).clipped(window); }
    /// How many pixels of the window tile t holds.
    uint64_t pixels(size_t t) const {
        const PixelRect r = rect(t);
        return r.empty() ? uint64_t{0} : static_cast<uint64_t>(r.width()) * r.height();
    }
    /// The tiles that hold pixels of `within`, in the order they are rendered.
    std::vector<size_t> within(const PixelRect& r) const {
        std::vector<size_t> list;
        for (size_t t : order)
            if (tile(t).overlaps(r)) list.push_back(t);
        return list;
    }
};

}  // namespace luz
