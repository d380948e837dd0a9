// The zbuffer pipeline: the scene tessellated once; per frame, the rasterizer bins the triangles
// into tiles and finds each tile's nearest fragments, and every one is shaded by shade()
// (deferred, once). Antialiasing drivers: render/zbuffer_antialias.cpp.
#include "render/zbuffer.h"

#include <algorithm>
#include <atomic>
#include <type_traits>
#include <vector>

#include "geometry/plane_grid.h"
#include "geometry/tessellate.h"
#include "render/parallel.h"
#include "render/rasterizer.h"
#include "render/sampler.h"
#include "render/zbuffer_antialias.h"
#include "render/zbuffer_shade.h"
#include "scene/camera.h"

namespace luz {

namespace {

/// Shades a tile's fragments into the image.
void shade_tile(const ZbufferFrame& f, int x0, int y0, int w, int h, const Fragment* frags,
                const uint32_t*, Image& out, RenderStats& stats) {
    const Lighting lighting = lighting_of(f.settings);
    const Rgb background = f.settings.image.background;
    for (int j = 0; j < h; ++j) {
        Rgb* row = &out.at(x0, y0 + j);
        const Fragment* frag = frags + static_cast<size_t>(j) * w;
        for (int i = 0; i < w; ++i) {
            row[i] = frag[i].triangle == kNoTriangle ? background
                                                     : shade_fragment(f, lighting, frag[i], stats);
        }
    }
}

/// The same with the terms (SPEC §1.5), `tests` holding each pixel's depth tests.
void shade_tile(const ZbufferFrame& f, int x0, int y0, int w, int h, const Fragment* frags,
                const uint32_t* tests, TermOut& out, RenderStats& stats) {
    const Lighting lighting = lighting_of(f.settings);
    for (int j = 0; j < h; ++j) {
        for (int i = 0; i < w; ++i) {
            const size_t k = static_cast<size_t>(j) * w + i;
            put(out, x0 + i, y0 + j, shade_fragment_terms(f, lighting, frags[k], tests[k], stats));
        }
    }
}

/// Step 3 of render_zbuffer(): every tile rasterized and shaded into `out` (an Image, or a
/// TermOut for the terms), with the frame's antialiasing.
template <class Out>
void render_tiles(const ZbufferFrame& f, const RenderControl& control, const GridSpec& grid,
                  Out& out, RenderStats& stats) {
    using S = SampleFor<Out>;
    constexpr bool kTerms = std::is_same_v<S, TermSample>;
    const Rasterizer& raster = f.raster;
    const ImageDesc& img = f.settings.image;
    const AntialiasDesc& aa = f.settings.render.antialias;
    const size_t tile_count = raster.tile_count();
    const size_t items = aa.mode == AaMode::adaptive ? 2 * tile_count : tile_count;
    std::vector<RenderStats> tile_stats(items);
    // --region: only the tiles that hold its pixels (whole tiles; the rest is left as it is);
    // adaptive's corners [x0, x1] × [y0, y1] come from the tiles of the region grown by one.
    const PixelRect window = render_window(control, img.width, img.height);
    const PixelRect grown = corner_window(window, img.width, img.height);
    auto tiles_within = [&](const PixelRect& within) {
        std::vector<size_t> list;
        for (size_t t = 0; t < tile_count; ++t)
            if (raster.tile_rect(t).overlaps(within)) list.push_back(t);
        return list;
    };
    const std::vector<size_t> tiles = tiles_within(window);
    const size_t reports =
        aa.mode == AaMode::adaptive ? tiles.size() + tiles_within(grown).size() : tiles.size();
    std::atomic<size_t> tiles_done{0};
    const auto cancelled = [&] {
        return control.cancel && control.cancel->load(std::memory_order_relaxed);
    };
    const auto report = [&] {
        const size_t done = ++tiles_done;
        if (control.progress) control.progress(static_cast<double>(done) / reports);
    };
    switch (aa.mode) {
        case AaMode::none:
            parallel_items(control.threads, tiles.size(), [&](size_t item) {
                if (cancelled()) return;
                const size_t t = tiles[item];
                const PixelRect r = raster.tile_rect(t);
                Fragment frags[kRasterTile * kRasterTile];
                uint32_t tests[kTerms ? kRasterTile * kRasterTile : 1];
                raster.rasterize(t, raster.centres(r), frags, kTerms ? tests : nullptr);
                shade_tile(f, r.x0, r.y0, r.width(), r.height(), frags, tests, out, tile_stats[t]);
                report();
            });
            break;
        case AaMode::grid:
            parallel_items(control.threads, tiles.size(), [&](size_t item) {
                if (cancelled()) return;
                const size_t t = tiles[item];
                grid_tile(f, t, grid, out, tile_stats[t]);
                report();
            });
            break;
        case AaMode::adaptive: {
            // Pass 1: every pixel corner (x, y integers), rasterized and shaded once.
            std::vector<S> corners(static_cast<size_t>(img.width + 1) * (img.height + 1));
            const std::vector<size_t> corner_tiles = tiles_within(grown);
            parallel_items(control.threads, corner_tiles.size(), [&](size_t item) {
                if (cancelled()) return;
                const size_t t = corner_tiles[item];
                adaptive_corners_tile(f, t, corners.data(), tile_stats[t]);
                report();
            });
            // Pass 2: pixels whose corners differ are refined on their finest lattice.
            const AdaptiveSpec spec = AdaptiveSpec::from(aa, img.width, img.height);
            parallel_items(control.threads, tiles.size(), [&](size_t item) {
                if (cancelled()) return;
                const size_t t = tiles[item];
                adaptive_refine_tile(f, t, spec, corners.data(), out, control.aa_mask,
                                     tile_stats[tile_count + t]);
                report();
            });
            break;
        }
    }
    for (const RenderStats& s : tile_stats) stats.add_counters(s);
}

void append_triangles_from(size_t first_index, int32_t material, ZbufferGeometry& g) {
    const TriangleMesh& m = g.mesh;
    for (size_t i = first_index; i < m.indices.size(); i += 3) {
        const Vec3& a = m.positions[m.indices[i]];
        const Vec3& b = m.positions[m.indices[i + 1]];
        const Vec3& c = m.positions[m.indices[i + 2]];
        const Vec3 n = cross(b - a, c - a);
        const float len = length(n);
        g.triangle_normal.push_back(len > 0 ? n / len : m.normals[m.indices[i]]);
        g.triangle_material.push_back(material);
    }
}

}  // namespace

ZbufferGeometry prepare_zbuffer(const BuiltScene& scene, const Settings& settings) {
    ZbufferGeometry g;
    const int level = scene.geometry.tessellation;
    for (const Shape& s : scene.shapes) {
        const size_t first = g.mesh.indices.size();
        if (s.type == ShapeType::plane) {
            append_plane_grid(scene, settings.camera, s, g.mesh);
        } else {
            tessellate(s, level, g.mesh);
        }
        append_triangles_from(first, s.material, g);
        if (s.mesh) {
            // a mesh's triangles, appended in order, each with its own material
            const size_t n = s.mesh->triangle_count();
            std::copy(s.mesh->materials.begin(), s.mesh->materials.end(),
                      g.triangle_material.end() - static_cast<std::ptrdiff_t>(n));
        }
    }
    // Visible light spheres, drawn in the light's clamped colour (SPEC §1.1).
    for (size_t j = 0; j < settings.lights.size(); ++j) {
        const Light& light = settings.lights[j];
        if (light.radius <= 0) continue;
        ObjectDesc o;
        o.type = ShapeType::sphere;
        o.center = light.position;
        o.radius = light.radius;
        const size_t first = g.mesh.indices.size();
        tessellate(make_shape(o, -1), level, g.mesh);
        append_triangles_from(first, -1 - static_cast<int32_t>(j), g);
    }
    return g;
}

void render_zbuffer(const BuiltScene& scene, const Settings& settings,
                    const ZbufferGeometry& geometry, const RenderControl& control, Image& out,
                    RenderStats& stats) {
    const ImageDesc& img = settings.image;
    const Camera camera = Camera::from(settings.camera, img.width, img.height);
    if (out.width != img.width || out.height != img.height) out = Image(img.width, img.height);

    // Antialiasing (SPEC §1.2) sets the raster's fixed-point unit and its tiles.
    const AntialiasDesc& aa = settings.render.antialias;
    const GridSpec grid = [&] {
        GridSpec g = GridSpec::from(aa, img.width, img.height);
        g.jitter = false;  // the zbuffer samples the regular grid (docs/ARCHITECTURE.md)
        return g;
    }();
    const RasterLayout layout = antialias_layout(aa, grid, img.width, img.height);
    if (control.aa_mask) {
        control.aa_mask->width = img.width;
        control.aa_mask->height = img.height;
        control.aa_mask->level.assign(static_cast<size_t>(img.width) * img.height, 0);
    }

    // 1–2. Project every vertex; clip and bin the triangles into tiles.
    const Rasterizer raster(geometry.mesh, camera, img.width, img.height, layout, control.threads);
    stats.triangles += raster.triangles();
    const ZbufferFrame f{scene,  settings, geometry,
                         raster, camera,   settings.camera.projection == Projection::perspective};

    // 3. Rasterize and shade each tile: the colours, or the colours and their terms.
    if (control.terms && control.terms->any()) {
        TermOut term_out{out, *control.terms};
        render_tiles(f, control, grid, term_out, stats);
    } else {
        render_tiles(f, control, grid, out, stats);
    }
}

}  // namespace luz
