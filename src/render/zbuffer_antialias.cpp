// Antialiasing in the zbuffer (docs/SCENES.md#antialiasing): the same sample positions, filters and
// refinement as the ray pipelines, on lattices of the rasterizer's fixed-point raster.
#include "render/zbuffer_antialias.h"

#include <algorithm>
#include <type_traits>
#include <vector>

namespace luz {

namespace {

/// Per-thread fragments of antialiased tiles (their lattices outgrow the stack).
std::vector<Fragment>& fragment_scratch() {
    thread_local std::vector<Fragment> frags;
    return frags;
}

/// Per-thread depth-test counts of a lattice, when terms are asked for (else null).
template <class S>
uint32_t* tests_scratch(size_t points) {
    if constexpr (std::is_same_v<S, Rgb>) {
        return nullptr;
    } else {
        thread_local std::vector<uint32_t> tests;
        tests.resize(points);
        return tests.data();
    }
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
template <class Sample>
struct ZbufferFine {
    const ZbufferFrame& f;
    size_t tile;
    const Lighting& lighting;
    RenderStats& stats;
    int S;
    Fragment* frags;  ///< (S+1)² fragments
    uint32_t* tests;  ///< their depth tests (terms), or null

    void begin_pixel(int i, int j) {
        const int64_t unit = f.raster.layout().unit;
        f.raster.rasterize(tile, Lattice{i * unit, j * unit, unit / S, S + 1, S + 1}, frags, tests);
    }
    auto colour(int, int, int k, int l) {
        const size_t p = static_cast<size_t>(l) * (S + 1) + k;
        return fragment_sample<Sample>(f, lighting, frags[p], tests ? tests[p] : 0, stats);
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

template <class Out>
void grid_tile(const ZbufferFrame& f, size_t t, const GridSpec& g, Out& out, RenderStats& stats) {
    using S = SampleFor<Out>;
    const PixelRect tile = f.raster.tile_rect(t), region = g.region(tile);
    const int s = g.s;
    const int64_t unit = f.raster.layout().unit;
    const Lattice lat{region.x0 * unit + unit / (2 * s), region.y0 * unit + unit / (2 * s),
                      unit / s, region.width() * s, region.height() * s};
    std::vector<Fragment>& frags = fragment_scratch();
    frags.resize(static_cast<size_t>(lat.w) * lat.h);
    uint32_t* tests = tests_scratch<S>(frags.size());
    f.raster.rasterize(t, lat, frags.data(), tests);
    std::vector<S>& colours = grid_scratch_for_this_thread<S>();
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
            colours[k] =
                inside || g.needed(tile, x, y)
                    ? fragment_sample<S>(f, lighting, frags[k], tests ? tests[k] : 0, stats)
                    : S{};
        }
    }
    filter_tile(g, tile, region, colours.data(), out);
}

template <class S>
void adaptive_corners_tile(const ZbufferFrame& f, size_t t, S* corners, RenderStats& stats) {
    const int W = f.raster.width(), H = f.raster.height();
    const PixelRect c = corner_rect(f.raster.tile_rect(t), W, H);
    const int64_t unit = f.raster.layout().unit;
    const Lattice lat{c.x0 * unit, c.y0 * unit, unit, c.width(), c.height()};
    std::vector<Fragment>& frags = fragment_scratch();
    frags.resize(static_cast<size_t>(lat.w) * lat.h);
    uint32_t* tests = tests_scratch<S>(frags.size());
    f.raster.rasterize(t, lat, frags.data(), tests);
    const Lighting lighting = lighting_of(f.settings);
    for (int y = 0; y < lat.h; ++y) {
        for (int x = 0; x < lat.w; ++x) {
            const size_t k = static_cast<size_t>(y) * lat.w + x;
            corners[static_cast<size_t>(c.y0 + y) * (W + 1) + c.x0 + x] =
                fragment_sample<S>(f, lighting, frags[k], tests ? tests[k] : 0, stats);
        }
    }
}

template <class Out>
void adaptive_refine_tile(const ZbufferFrame& f, size_t t, const AdaptiveSpec& spec,
                          const SampleFor<Out>* corners, Out& out, AaMask* mask,
                          RenderStats& stats) {
    using Sample = SampleFor<Out>;
    const Lighting lighting = lighting_of(f.settings);
    const int S = spec.lattice();
    std::vector<Fragment>& frags = fragment_scratch();
    frags.resize(static_cast<size_t>(S + 1) * (S + 1));
    ZbufferFine<Sample> fine{
        f, t, lighting, stats, S, frags.data(), tests_scratch<Sample>(frags.size())};
    SamplerCounts counts;
    refine_tile(spec, f.raster.tile_rect(t), corners, fine, out, mask, counts);
    stats.pixels_refined += counts.pixels_refined;
}

// The two kinds of output: colours alone, and colours with their terms.
template void grid_tile<Image>(const ZbufferFrame&, size_t, const GridSpec&, Image&, RenderStats&);
template void grid_tile<TermOut>(const ZbufferFrame&, size_t, const GridSpec&, TermOut&,
                                 RenderStats&);
template void adaptive_corners_tile<Rgb>(const ZbufferFrame&, size_t, Rgb*, RenderStats&);
template void adaptive_corners_tile<TermSample>(const ZbufferFrame&, size_t, TermSample*,
                                                RenderStats&);
template void adaptive_refine_tile<Image>(const ZbufferFrame&, size_t, const AdaptiveSpec&,
                                          const Rgb*, Image&, AaMask*, RenderStats&);
template void adaptive_refine_tile<TermOut>(const ZbufferFrame&, size_t, const AdaptiveSpec&,
                                            const TermSample*, TermOut&, AaMask*, RenderStats&);

}  // namespace luz
