// Antialiasing in the zbuffer (SPEC §1.2): the same sample positions, filters and refinement as
// the ray pipelines, on lattices of the rasterizer's fixed-point raster.
#include "render/zbuffer_antialias.h"

#include <algorithm>
#include <vector>

namespace luz {

namespace {

/// Per-thread fragments of antialiased tiles (their lattices outgrow the stack).
std::vector<Fragment>& fragment_scratch() {
    thread_local std::vector<Fragment> frags;
    return frags;
}

/// Grid antialiasing: fixed-point units per pixel, a multiple of 2s so that every sample
/// (i + (a+0.5)/s) is exact — 256·s unless the guard band would then overflow 32 bits.
int64_t grid_unit(int s, int width, int height) {
    int64_t k = 128;
    const int64_t extent = static_cast<int64_t>(kGuardBand / 2 + 1) * std::max(width, height);
    while (k > 1 && extent * 2 * s * k >= (int64_t{1} << 31)) k /= 2;
    return 2 * s * k;
}

/// Grid antialiasing: tile side in pixels, so that a tile's samples and the tent's ring stay
/// under ~300×300.
int grid_tile_size(int s) { return s <= 4 ? kRasterTile : (s <= 8 ? 32 : 16); }

/// Adaptive antialiasing in the zbuffer: the sub-corners of a refined pixel. Its finest
/// lattice (i + k/S, j + l/S) is rasterized once (coverage and depth); the refinement then
/// shades only the points it asks for.
struct ZbufferFine {
    const ZbufferFrame& f;
    size_t tile;
    const Lighting& lighting;
    RenderStats& stats;
    int S;
    Fragment* frags;  ///< (S+1)² fragments

    void begin_pixel(int i, int j) {
        const int64_t unit = f.raster.layout().unit;
        f.raster.rasterize(tile, Lattice{i * unit, j * unit, unit / S, S + 1, S + 1}, frags);
    }
    Rgb colour(int, int, int k, int l) {
        return shade_fragment(f, lighting, frags[static_cast<size_t>(l) * (S + 1) + k], stats);
    }
};

}  // namespace

RasterLayout antialias_layout(const AntialiasDesc& aa, const GridSpec& grid, int width,
                              int height) {
    RasterLayout layout;
    if (aa.mode == AaMode::grid) {
        layout.unit = grid_unit(grid.s, width, height);
        layout.tile = grid_tile_size(grid.s);
        layout.margin = aa.filter == AaFilter::tent ? 1 : 0;
    } else if (aa.mode == AaMode::adaptive) {
        layout.tile = kSamplerTile;
        layout.margin = 1;  // corners on a tile's right and bottom borders
    }
    return layout;
}

void grid_tile(const ZbufferFrame& f, size_t t, const GridSpec& g, Image& out, RenderStats& stats) {
    const PixelRect tile = f.raster.tile_rect(t), region = g.region(tile);
    const int s = g.s;
    const int64_t unit = f.raster.layout().unit;
    const Lattice lat{region.x0 * unit + unit / (2 * s), region.y0 * unit + unit / (2 * s),
                      unit / s, region.width() * s, region.height() * s};
    std::vector<Fragment>& frags = fragment_scratch();
    frags.resize(static_cast<size_t>(lat.w) * lat.h);
    f.raster.rasterize(t, lat, frags.data());
    std::vector<Rgb>& colours = grid_scratch_for_this_thread();
    colours.resize(frags.size());
    const Lighting lighting = lighting_of(f.settings);
    for (int b = 0; b < lat.h; ++b) {
        const int j = region.y0 + b / s;
        for (int a = 0; a < lat.w; ++a) {
            const int i = region.x0 + a / s;
            const bool inside = i >= tile.x0 && i < tile.x1 && j >= tile.y0 && j < tile.y1;
            float x, y;
            g.position(i, j, a % s, b % s, x, y);
            const size_t k = static_cast<size_t>(b) * lat.w + a;
            colours[k] = inside || g.needed(tile, x, y)
                             ? shade_fragment(f, lighting, frags[k], stats)
                             : Rgb{0.0f};
        }
    }
    filter_tile(g, tile, region, colours.data(), out);
}

void adaptive_corners_tile(const ZbufferFrame& f, size_t t, Rgb* corners, RenderStats& stats) {
    const int W = f.raster.width(), H = f.raster.height();
    const PixelRect c = corner_rect(f.raster.tile_rect(t), W, H);
    const int64_t unit = f.raster.layout().unit;
    const Lattice lat{c.x0 * unit, c.y0 * unit, unit, c.width(), c.height()};
    std::vector<Fragment>& frags = fragment_scratch();
    frags.resize(static_cast<size_t>(lat.w) * lat.h);
    f.raster.rasterize(t, lat, frags.data());
    const Lighting lighting = lighting_of(f.settings);
    for (int y = 0; y < lat.h; ++y)
        for (int x = 0; x < lat.w; ++x)
            corners[static_cast<size_t>(c.y0 + y) * (W + 1) + c.x0 + x] =
                shade_fragment(f, lighting, frags[static_cast<size_t>(y) * lat.w + x], stats);
}

void adaptive_refine_tile(const ZbufferFrame& f, size_t t, const AdaptiveSpec& spec,
                          const Rgb* corners, Image& out, AaMask* mask, RenderStats& stats) {
    const Lighting lighting = lighting_of(f.settings);
    const int S = spec.lattice();
    std::vector<Fragment>& frags = fragment_scratch();
    frags.resize(static_cast<size_t>(S + 1) * (S + 1));
    ZbufferFine fine{f, t, lighting, stats, S, frags.data()};
    SamplerCounts counts;
    refine_tile(spec, f.raster.tile_rect(t), corners, fine, out, mask, counts);
    stats.pixels_refined += counts.pixels_refined;
}

}  // namespace luz
