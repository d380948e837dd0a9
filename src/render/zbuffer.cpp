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
#include "render/stats.h"  // add_counters()
#include "render/work_items.h"
#include "render/zbuffer_antialias.h"
#include "render/zbuffer_shade.h"
#include "scene/camera.h"
#include "scene/cancel.h"

namespace luz {

namespace {

/// Shades a tile's fragments into the image, eight at a time along each row
/// (shade_fragments_lanes()), the last few of a row one at a time.
void shade_tile(const ZbufferFrame& f, int x0, int y0, int w, int h, const Fragment* frags,
                const uint32_t*, Image& out, RenderStats& stats) {
    const Lighting lighting = lighting_of(f.settings);
    for (int j = 0; j < h; ++j) {
        Rgb* row = &out.at(x0, y0 + j);
        const Fragment* frag = frags + static_cast<size_t>(j) * w;
        int i = 0;
        for (; i + kPacketLanes <= w; i += kPacketLanes)
            shade_fragments_lanes(f, lighting, frag + i, row + i, stats);
        for (; i < w; ++i) row[i] = shade_fragment(f, lighting, frag[i], stats);
    }
}

/// The same with the terms (docs/SCENES.md#terms), `tests` holding each pixel's depth tests.
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
    const auto report = [&](size_t) {
        const size_t done = ++tiles_done;
        if (control.progress) control.progress(static_cast<double>(done) / reports);
    };
    // A tile's bytes (MPI; the zbuffer keeps no checkpoint): its counters, then its pixels.
    const auto write_stats = [](std::string& o, const RenderStats& s) {
        for (uint64_t v :
             {s.rays_primary, s.rays_shadow, s.rays_reflection, s.rays_refraction,
              s.tests_primitive, s.tests_bounds, s.pixels_refined, s.samples, s.triangles})
            append_raw(o, v);
    };
    const auto read_stats = [](std::string_view& in, RenderStats& s) {
        for (uint64_t* v :
             {&s.rays_primary, &s.rays_shadow, &s.rays_reflection, &s.rays_refraction,
              &s.tests_primitive, &s.tests_bounds, &s.pixels_refined, &s.samples, &s.triangles})
            read_raw(in, *v);
    };
    const auto rays = [](size_t) { return uint64_t{0}; };  // the zbuffer traces no rays
    // Adaptive's refinement levels of tile t (the --aa-mask's bytes).
    const auto mask_levels = [&](size_t t, auto&& each) {
        if (!control.aa_mask) return;
        const PixelRect r = raster.tile_rect(t);
        for (int y = r.y0; y < r.y1; ++y)
            for (int x = r.x0; x < r.x1; ++x)
                each(control.aa_mask->level[static_cast<size_t>(y) * img.width + x]);
    };
    // Colours (and terms) of tile t, counted in tile_stats[base + t], with adaptive's levels
    // when `levels`.
    const auto pixel_code = [&](auto&& render, size_t base, bool levels) {
        return TileCode{render,
                        [&, base, levels](size_t t, std::string& o) {
                            write_stats(o, tile_stats[base + t]);
                            append_rect(o, out, raster.tile_rect(t));
                            if (levels) mask_levels(t, [&](uint8_t v) { append_raw(o, v); });
                        },
                        [&, base, levels](size_t t, std::string_view& in) {
                            read_stats(in, tile_stats[base + t]);
                            read_rect(in, out, raster.tile_rect(t));
                            if (levels) mask_levels(t, [&](uint8_t& v) { read_raw(in, v); });
                        }};
    };
    switch (aa.mode) {
        case AaMode::none: {
            auto code = pixel_code(
                [&](size_t t) {
                    const PixelRect r = raster.tile_rect(t);
                    Fragment frags[kRasterTile * kRasterTile];
                    uint32_t tests[kTerms ? kRasterTile * kRasterTile : 1];
                    raster.rasterize(t, raster.centres(r), frags, kTerms ? tests : nullptr);
                    shade_tile(f, r.x0, r.y0, r.width(), r.height(), frags, tests, out,
                               tile_stats[t]);
                    report(t);
                },
                0, false);
            run_pass(control, nullptr, tiles, 0, false, code, report, rays);
            break;
        }
        case AaMode::grid: {
            auto code = pixel_code(
                [&](size_t t) {
                    grid_tile(f, t, grid, out, tile_stats[t]);
                    report(t);
                },
                0, false);
            run_pass(control, nullptr, tiles, 0, false, code, report, rays);
            break;
        }
        case AaMode::adaptive: {
            // Pass 1: every pixel corner (x, y integers), rasterized and shaded once; every
            // process needs them all for pass 2.
            std::vector<S> corners(static_cast<size_t>(img.width + 1) * (img.height + 1));
            const std::vector<size_t> corner_tiles = tiles_within(grown);
            const auto corner_values = [&](size_t t, auto&& each) {
                const PixelRect c = corner_rect(raster.tile_rect(t), img.width, img.height);
                for (int y = c.y0; y < c.y1; ++y)
                    for (int x = c.x0; x < c.x1; ++x)
                        each(corners[static_cast<size_t>(y) * (img.width + 1) + x]);
            };
            auto pass1 = TileCode{[&](size_t t) {
                                      adaptive_corners_tile(f, t, corners.data(), tile_stats[t]);
                                      report(t);
                                  },
                                  [&](size_t t, std::string& o) {
                                      write_stats(o, tile_stats[t]);
                                      corner_values(t, [&](const S& v) { append_raw(o, v); });
                                  },
                                  [&](size_t t, std::string_view& in) {
                                      read_stats(in, tile_stats[t]);
                                      corner_values(t, [&](S& v) { read_raw(in, v); });
                                  }};
            run_pass(control, nullptr, corner_tiles, 0, true, pass1, report, rays);
            // Pass 2: pixels whose corners differ are refined on their finest lattice.
            const AdaptiveSpec spec = AdaptiveSpec::from(aa, img.width, img.height);
            auto pass2 = pixel_code(
                [&](size_t t) {
                    adaptive_refine_tile(f, t, spec, corners.data(), out, control.aa_mask,
                                         tile_stats[tile_count + t]);
                    report(t);
                },
                tile_count, true);
            run_pass(control, nullptr, tiles, tile_count, false, pass2, report, rays);
            break;
        }
    }
    for (const RenderStats& s : tile_stats) add_counters(stats, s);
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
    g.raster_spare = std::make_shared<RasterSpare>();
    const int level = scene.geometry.tessellation;
    for (const Shape& s : scene.shapes) {
        check_cancel();  // thousands of shapes take a while to tessellate
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
    // Visible light spheres, drawn in the light's clamped colour (docs/SCENES.md#ray-tracing).
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

    // Antialiasing (docs/SCENES.md#antialiasing) sets the raster's fixed-point unit and its tiles.
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
    const Rasterizer raster(geometry.mesh, camera, img.width, img.height, layout, control.threads,
                            geometry.raster_spare.get());
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
