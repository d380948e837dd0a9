// The zbuffer pipeline: triangles are projected, clipped against the camera plane and a guard
// band, binned into screen tiles, rasterized with fixed-point edge functions (top-left rule)
// and a float depth buffer, and every covered pixel is shaded by shade() (deferred, once).
#include "render/zbuffer.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>

#include "geometry/tessellate.h"
#include "render/parallel.h"
#include "render/sampler.h"
#include "scene/camera.h"
#include "shading/shade.h"

namespace luz {

namespace {

constexpr int kTileSize = 64;         // pixels per tile side
constexpr int kSubpixelBits = 8;      // fixed-point precision of vertex positions
constexpr float kGuardBand = 16.0f;   // clip where |x| or |y| exceeds this many half-images
constexpr size_t kChunkSize = 16384;  // triangles per binning task (fixed: determinism)
constexpr uint32_t kNoTriangle = std::numeric_limits<uint32_t>::max();

/// A vertex in clip space: x, y in half-image units times w, depth along the view, w.
struct ClipVertex {
    float x, y, depth, w;
    Vec3 bary;  ///< barycentric coordinates in the original triangle
};

/// A triangle ready to rasterize: fixed-point screen vertices, per-vertex depth and 1/w.
struct RasterTriangle {
    int32_t x[3], y[3];  ///< pixel coordinates · 2^kSubpixelBits
    float depth[3];      ///< view depth (orthographic: interpolated linearly on screen)
    float inv_w[3];      ///< 1/w (perspective-correct interpolation; 1 when orthographic)
    uint32_t triangle;   ///< index of the original triangle
    int32_t clip;        ///< −1, or index of its vertices' barycentrics in Bin::clip_bary
};

/// The triangles one chunk sends to each tile, in triangle order.
struct ChunkBins {
    std::vector<RasterTriangle> triangles;
    std::vector<std::array<Vec3, 3>> clip_bary;
    std::vector<std::vector<uint32_t>> tile_lists;  ///< per tile: indices into triangles
};

struct Frame {
    const BuiltScene& scene;
    const Settings& settings;
    const ZbufferGeometry& geometry;
    Camera camera;
    bool perspective;
    int width, height, tiles_x, tiles_y;
    std::vector<ClipVertex> vertices;            ///< projected mesh positions
    int64_t unit = int64_t{1} << kSubpixelBits;  ///< fixed-point units per pixel
    int tile = kTileSize;                        ///< pixels per tile side
    int margin = 0;  ///< pixels a triangle's box grows by when binned (samples on tile borders)
};

/// ⌊a / b⌋ and ⌈a / b⌉ for b > 0.
int64_t floor_div(int64_t a, int64_t b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }
int64_t ceil_div(int64_t a, int64_t b) { return -floor_div(-a, b); }

ClipVertex project(const Camera& cam, bool perspective, const Vec3& p) {
    const Vec3 v = cam.to_view(p);
    ClipVertex c;
    c.x = v.x / cam.half_width;
    c.y = v.y / cam.half_height;
    c.depth = v.z;
    c.w = perspective ? v.z : 1.0f;
    return c;
}

/// Signed distance to one clip plane; inside where ≥ 0. Planes: 0 near (camera plane),
/// 1..4 guard band left, right, bottom, top.
float plane_distance(const ClipVertex& v, int plane, float near) {
    switch (plane) {
        case 0:
            return v.depth - near;
        case 1:
            return v.x + kGuardBand * v.w;
        case 2:
            return kGuardBand * v.w - v.x;
        case 3:
            return v.y + kGuardBand * v.w;
        default:
            return kGuardBand * v.w - v.y;
    }
}

ClipVertex lerp(const ClipVertex& a, const ClipVertex& b, float t) {
    return {a.x + (b.x - a.x) * t, a.y + (b.y - a.y) * t, a.depth + (b.depth - a.depth) * t,
            a.w + (b.w - a.w) * t, a.bary + (b.bary - a.bary) * t};
}

/// Sutherland–Hodgman clipping of a convex polygon against the planes in `mask`.
int clip_polygon(ClipVertex* poly, int n, unsigned mask, float near) {
    ClipVertex tmp[16];
    for (int plane = 0; plane < 5 && n > 0; ++plane) {
        if (!(mask & (1u << plane))) continue;
        int m = 0;
        for (int i = 0; i < n; ++i) {
            const ClipVertex& a = poly[i];
            const ClipVertex& b = poly[(i + 1) % n];
            const float da = plane_distance(a, plane, near), db = plane_distance(b, plane, near);
            if (da >= 0) tmp[m++] = a;
            if ((da >= 0) != (db >= 0)) tmp[m++] = lerp(a, b, da / (da - db));
        }
        std::copy(tmp, tmp + m, poly);
        n = m;
    }
    return n;
}

/// The near plane: the camera plane for orthographic views; a small positive depth for
/// perspective, where w must stay positive.
float near_depth(const Frame& f) { return f.perspective ? 1e-4f : 0.0f; }

/// Screen-space setup of a clipped or unclipped triangle; false if it covers no area.
bool setup(const Frame& f, const ClipVertex* v, uint32_t triangle, RasterTriangle& r) {
    const double sx = 0.5 * f.width * static_cast<double>(f.unit);
    const double sy = 0.5 * f.height * static_cast<double>(f.unit);
    for (int i = 0; i < 3; ++i) {
        const float iw = 1.0f / v[i].w;
        // px = (x+1)·W/2, py = (1−y)·H/2 (SPEC §1.3), in fixed point.
        r.x[i] = static_cast<int32_t>(std::lround((double{v[i].x} * iw + 1.0) * sx));
        r.y[i] = static_cast<int32_t>(std::lround((1.0 - double{v[i].y} * iw) * sy));
        r.depth[i] = v[i].depth;
        r.inv_w[i] = iw;
    }
    r.triangle = triangle;
    r.clip = -1;
    const int64_t area = static_cast<int64_t>(r.x[1] - r.x[0]) * (r.y[2] - r.y[0]) -
                         static_cast<int64_t>(r.y[1] - r.y[0]) * (r.x[2] - r.x[0]);
    return area != 0;
}

/// Adds a set-up triangle to the bins of the tiles its bounding box touches.
void bin(const Frame& f, ChunkBins& bins, const RasterTriangle& r) {
    const auto pixel = [&](int32_t v, int grow) {
        return static_cast<int32_t>(floor_div(v, f.unit)) + grow;
    };
    const int32_t lo_x = pixel(std::min({r.x[0], r.x[1], r.x[2]}), -f.margin);
    const int32_t hi_x = pixel(std::max({r.x[0], r.x[1], r.x[2]}), f.margin);
    const int32_t lo_y = pixel(std::min({r.y[0], r.y[1], r.y[2]}), -f.margin);
    const int32_t hi_y = pixel(std::max({r.y[0], r.y[1], r.y[2]}), f.margin);
    if (hi_x < 0 || hi_y < 0 || lo_x >= f.width || lo_y >= f.height) return;
    const int tx0 = std::max(0, lo_x / f.tile), tx1 = std::min(f.tiles_x - 1, hi_x / f.tile);
    const int ty0 = std::max(0, lo_y / f.tile), ty1 = std::min(f.tiles_y - 1, hi_y / f.tile);
    const auto index = static_cast<uint32_t>(bins.triangles.size());
    bins.triangles.push_back(r);
    for (int ty = ty0; ty <= ty1; ++ty)
        for (int tx = tx0; tx <= tx1; ++tx) bins.tile_lists[ty * f.tiles_x + tx].push_back(index);
}

/// Projects, clips and bins triangles [begin, end).
void bin_chunk(const Frame& f, size_t begin, size_t end, ChunkBins& bins) {
    const TriangleMesh& mesh = f.geometry.mesh;
    const float near = near_depth(f);
    bins.tile_lists.assign(static_cast<size_t>(f.tiles_x) * f.tiles_y, {});
    for (size_t t = begin; t < end; ++t) {
        ClipVertex v[3];
        unsigned outside_all = 0x1f, outside_any = 0;
        for (int i = 0; i < 3; ++i) {
            v[i] = f.vertices[mesh.indices[3 * t + i]];
            unsigned out = 0;
            for (int p = 0; p < 5; ++p)
                if (plane_distance(v[i], p, near) < 0) out |= 1u << p;
            outside_all &= out;
            outside_any |= out;
        }
        if (outside_all) continue;  // entirely outside one plane
        const auto tri = static_cast<uint32_t>(t);
        RasterTriangle r;
        if (!outside_any) {
            if (setup(f, v, tri, r)) bin(f, bins, r);
            continue;
        }
        ClipVertex poly[16] = {v[0], v[1], v[2]};
        poly[0].bary = {1, 0, 0};
        poly[1].bary = {0, 1, 0};
        poly[2].bary = {0, 0, 1};
        const int n = clip_polygon(poly, 3, outside_any, near);
        for (int i = 1; i + 1 < n; ++i) {
            const ClipVertex fan[3] = {poly[0], poly[i], poly[i + 1]};
            if (!setup(f, fan, tri, r)) continue;
            r.clip = static_cast<int32_t>(bins.clip_bary.size());
            bins.clip_bary.push_back({fan[0].bary, fan[1].bary, fan[2].bary});
            bin(f, bins, r);
        }
    }
}

/// What the depth pass keeps per pixel: the nearest triangle and its barycentrics there.
struct Fragment {
    float depth;
    uint32_t triangle;
    float b1, b2;  ///< perspective-correct barycentrics of vertices 1 and 2
};

/// The points a tile is rasterized at: point (a, b) at (x0 + a·step, y0 + b·step) in fixed
/// point, 0 ≤ a < w, 0 ≤ b < h; its fragment is frags[b·w + a]. Pixel centres, antialiasing
/// samples and pixel corners are all such lattices.
struct Lattice {
    int64_t x0, y0, step;
    int w, h;
};

/// The lattice of the pixel centres of a tile.
Lattice centres(const Frame& f, int x0, int y0, int w, int h) {
    return {x0 * f.unit + f.unit / 2, y0 * f.unit + f.unit / 2, f.unit, w, h};
}

/// Rasterizes one triangle into a lattice's fragments (top-left fill rule).
void rasterize(const Frame& f, const RasterTriangle& r, const std::array<Vec3, 3>* clip_bary,
               const Lattice& lat, Fragment* frags) {
    int64_t x[3] = {r.x[0], r.x[1], r.x[2]}, y[3] = {r.y[0], r.y[1], r.y[2]};
    int order[3] = {0, 1, 2};
    // Edge functions are positive inside for a counter-clockwise triangle on screen (y down).
    int64_t area = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
    if (area < 0) {
        std::swap(x[1], x[2]);
        std::swap(y[1], y[2]);
        std::swap(order[1], order[2]);
        area = -area;
    }
    const int64_t step = lat.step;
    // Lattice range of the bounding box.
    const int64_t min_x = std::min({x[0], x[1], x[2]}), max_x = std::max({x[0], x[1], x[2]});
    const int64_t min_y = std::min({y[0], y[1], y[2]}), max_y = std::max({y[0], y[1], y[2]});
    const int px0 = static_cast<int>(std::max<int64_t>(0, ceil_div(min_x - lat.x0, step)));
    const int px1 = static_cast<int>(std::min<int64_t>(lat.w - 1, floor_div(max_x - lat.x0, step)));
    const int py0 = static_cast<int>(std::max<int64_t>(0, ceil_div(min_y - lat.y0, step)));
    const int py1 = static_cast<int>(std::min<int64_t>(lat.h - 1, floor_div(max_y - lat.y0, step)));
    if (px0 > px1 || py0 > py1) return;

    // Edge k is opposite vertex k: E_k(p) = (b − a) × (p − a) for a = v[k+1], b = v[k+2].
    int64_t ex[3], ey[3], e0[3], bias[3];
    const int64_t sx = lat.x0 + px0 * step, sy = lat.y0 + py0 * step;
    for (int k = 0; k < 3; ++k) {
        const int a = (k + 1) % 3, b = (k + 2) % 3;
        const int64_t dx = x[b] - x[a], dy = y[b] - y[a];
        // Inside: E_k = dx·(py − ya) − dy·(px − xa) ≥ 0 (y down, positive area).
        ex[k] = -dy * step;  // change per lattice step in x
        ey[k] = dx * step;   // change per lattice step in y
        e0[k] = dx * (sy - y[a]) - dy * (sx - x[a]);
        // Top-left rule: a lattice point exactly on an edge belongs to the triangle only if the
        // edge is a top edge (horizontal, interior below) or a left edge.
        const bool top = dy == 0 && dx > 0;
        const bool left = dy < 0;
        bias[k] = (top || left) ? 0 : 1;
        e0[k] -= bias[k];
    }
    const float inv_area = 1.0f / static_cast<float>(area);
    const float d[3] = {r.depth[order[0]], r.depth[order[1]], r.depth[order[2]]};
    const float iw[3] = {r.inv_w[order[0]], r.inv_w[order[1]], r.inv_w[order[2]]};
    const bool persp = f.perspective;
    for (int py = py0; py <= py1; ++py) {
        int64_t w0 = e0[0], w1 = e0[1], w2 = e0[2];
        Fragment* row = frags + static_cast<size_t>(py) * lat.w;
        for (int px = px0; px <= px1; ++px) {
            if ((w0 | w1 | w2) >= 0) {
                // Screen-space barycentrics λ (without the top-left bias).
                const float l1 = static_cast<float>(w1 + bias[1]) * inv_area;
                const float l2 = static_cast<float>(w2 + bias[2]) * inv_area;
                const float l0 = 1.0f - l1 - l2;
                float depth, b[3];
                if (persp) {
                    // 1/w is linear on screen: perspective-correct interpolation.
                    const float q0 = l0 * iw[0], q1 = l1 * iw[1], q2 = l2 * iw[2];
                    const float inv = 1.0f / (q0 + q1 + q2);
                    b[0] = q0 * inv;
                    b[1] = q1 * inv;
                    b[2] = q2 * inv;
                    depth = b[0] * d[0] + b[1] * d[1] + b[2] * d[2];
                } else {
                    b[0] = l0;
                    b[1] = l1;
                    b[2] = l2;
                    depth = l0 * d[0] + l1 * d[1] + l2 * d[2];
                }
                Fragment& frag = row[px];
                if (depth < frag.depth) {
                    // Barycentrics of the set-up vertices → of the original triangle.
                    float o[3] = {0, 0, 0};
                    for (int k = 0; k < 3; ++k) o[order[k]] = b[k];
                    if (clip_bary) {
                        const auto& cb = *clip_bary;
                        const Vec3 ob = cb[0] * o[0] + cb[1] * o[1] + cb[2] * o[2];
                        o[1] = ob.y;
                        o[2] = ob.z;
                    }
                    frag = {depth, r.triangle, o[1], o[2]};
                }
            }
            w0 += ex[0];
            w1 += ex[1];
            w2 += ex[2];
        }
        e0[0] += ey[0];
        e0[1] += ey[1];
        e0[2] += ey[2];
    }
}

Lighting lighting_of(const Settings& desc) {
    return {desc.render.model, desc.ambient, desc.attenuation_k, desc.lights};
}

/// The colour of one fragment: the background, a light sphere's clamped colour, or shade() at
/// its point (counted as a sample).
[[gnu::always_inline]] inline Rgb shade_fragment(const Frame& f, const Lighting& lighting,
                                                 const Fragment& frag, RenderStats& stats) {
    const Settings& desc = f.settings;
    const TriangleMesh& mesh = f.geometry.mesh;
    if (frag.triangle == kNoTriangle) return desc.image.background;
    const int32_t material = f.geometry.triangle_material[frag.triangle];
    if (material < 0) {  // a visible light sphere: the light's clamped colour
        return clamp01(desc.lights[-1 - material].intensity);
    }
    const uint32_t* idx = &mesh.indices[3 * static_cast<size_t>(frag.triangle)];
    const float b0 = 1.0f - frag.b1 - frag.b2;
    ShadingPoint p;
    p.P = mesh.positions[idx[0]] * b0 + mesh.positions[idx[1]] * frag.b1 +
          mesh.positions[idx[2]] * frag.b2;
    p.N = normalize(mesh.normals[idx[0]] * b0 + mesh.normals[idx[1]] * frag.b1 +
                    mesh.normals[idx[2]] * frag.b2);
    p.Ng = f.geometry.triangle_normal[frag.triangle];
    p.S = f.perspective ? normalize(f.camera.position - p.P) : f.camera.w;
    p.material = &desc.materials[material];
    ++stats.samples;
    return shade(p, lighting, AllVisible{});
}

/// Shades a tile's fragments into the image.
void shade_tile(const Frame& f, int x0, int y0, int w, int h, const Fragment* frags, Image& out,
                RenderStats& stats) {
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

constexpr Fragment kEmptyFragment{std::numeric_limits<float>::infinity(), kNoTriangle, 0, 0};

/// Rasterizes the triangles binned to tile `t` into the fragments of lattice `lat`, chunks in
/// order, so that ties resolve the same way always.
void rasterize_bins(const Frame& f, const std::vector<ChunkBins>& chunks, size_t t,
                    const Lattice& lat, Fragment* frags) {
    std::fill(frags, frags + static_cast<size_t>(lat.w) * lat.h, kEmptyFragment);
    for (const ChunkBins& c : chunks) {
        for (uint32_t index : c.tile_lists[t]) {
            const RasterTriangle& r = c.triangles[index];
            rasterize(f, r, r.clip >= 0 ? &c.clip_bary[r.clip] : nullptr, lat, frags);
        }
    }
}

PixelRect tile_rect(const Frame& f, size_t t) {
    const int x0 = static_cast<int>(t % f.tiles_x) * f.tile;
    const int y0 = static_cast<int>(t / f.tiles_x) * f.tile;
    return {x0, y0, std::min(f.width, x0 + f.tile), std::min(f.height, y0 + f.tile)};
}

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
int grid_tile_size(int s) { return s <= 4 ? kTileSize : (s <= 8 ? 32 : 16); }

/// Grid antialiasing of tile `t` (SPEC §1.2): the samples of its pixels (and of the ring the
/// tent filter reaches) are the centres of the sub-pixels of a raster s times finer — one
/// lattice rasterized at once, shaded, then filtered into the image.
void grid_tile(const Frame& f, const std::vector<ChunkBins>& chunks, size_t t, const GridSpec& g,
               Image& out, RenderStats& stats) {
    const PixelRect tile = tile_rect(f, t), region = g.region(tile);
    const int s = g.s;
    const Lattice lat{region.x0 * f.unit + f.unit / (2 * s), region.y0 * f.unit + f.unit / (2 * s),
                      f.unit / s, region.width() * s, region.height() * s};
    std::vector<Fragment>& frags = fragment_scratch();
    frags.resize(static_cast<size_t>(lat.w) * lat.h);
    rasterize_bins(f, chunks, t, lat, frags.data());
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

/// Adaptive antialiasing in the zbuffer: the sub-corners of a refined pixel. Its finest
/// lattice (i + k/S, j + l/S) is rasterized once (coverage and depth); the refinement then
/// shades only the points it asks for.
struct ZbufferFine {
    const Frame& f;
    const std::vector<ChunkBins>& chunks;
    size_t tile;
    const Lighting& lighting;
    RenderStats& stats;
    int S;
    Fragment* frags;  ///< (S+1)² fragments

    void begin_pixel(int i, int j) {
        rasterize_bins(f, chunks, tile, Lattice{i * f.unit, j * f.unit, f.unit / S, S + 1, S + 1},
                       frags);
    }
    Rgb colour(int, int, int k, int l) {
        return shade_fragment(f, lighting, frags[static_cast<size_t>(l) * (S + 1) + k], stats);
    }
};

/// The scene's size: the diagonal of everything bounded, the camera and what it looks at.
float scene_size(const BuiltScene& scene, const Settings& settings) {
    Bounds3 b;
    for (const Shape& s : scene.shapes)
        if (is_bounded(s)) b.expand(bounds(s));
    const CameraDesc& c = settings.camera;
    b.expand(c.position);
    b.expand(c.look_at);
    return std::max(length(b.extent()) + c.view_height, 1.0f);
}

/// An unbounded plane as a square far larger than the scene, centred at the camera's foot
/// on the plane, made of a grid whose cells double in size away from the centre: every point
/// is interpolated from nearby vertices, so positions (and checker cells) stay precise.
void append_plane(const BuiltScene& scene, const Settings& settings, const Shape& s,
                  TriangleMesh& mesh) {
    const float size = scene_size(scene, settings);
    const Vec3 o = s.transform.point({0, 0, 0});
    const Vec3 n = normalize(s.transform.normal({0, 0, 1}));
    const Vec3 eye = settings.camera.position;
    const Vec3 foot = eye - n * dot(eye - o, n);
    Vec3 u, v;
    orthonormal_basis(n, u, v);
    std::vector<float> coords{0.0f};
    for (float c = size / 16; c < 1000 * size; c *= 2) {
        coords.push_back(c);
        coords.insert(coords.begin(), -c);
    }
    const auto k = static_cast<uint32_t>(coords.size());
    const auto base = static_cast<uint32_t>(mesh.positions.size());
    for (float cv : coords) {
        for (float cu : coords) {
            mesh.positions.push_back(foot + u * cu + v * cv);
            mesh.normals.push_back(n);
        }
    }
    for (uint32_t j = 0; j + 1 < k; ++j) {
        for (uint32_t i = 0; i + 1 < k; ++i) {
            const uint32_t a = base + j * k + i, b = a + 1, c = a + k + 1, d = a + k;
            for (uint32_t index : {a, b, c, a, c, d}) mesh.indices.push_back(index);
        }
    }
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
            append_plane(scene, settings, s, g.mesh);
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
    Frame f{scene,
            settings,
            geometry,
            Camera::from(settings.camera, img.width, img.height),
            settings.camera.projection == Projection::perspective,
            img.width,
            img.height,
            0,
            0,
            {}};
    if (out.width != img.width || out.height != img.height) out = Image(img.width, img.height);

    // Antialiasing (SPEC §1.2) sets the raster's fixed-point unit and its tiles.
    const AntialiasDesc& aa = settings.render.antialias;
    const GridSpec grid = [&] {
        GridSpec g = GridSpec::from(aa, img.width, img.height);
        g.jitter = false;  // the zbuffer samples the regular grid (docs/ARCHITECTURE.md)
        return g;
    }();
    if (aa.mode == AaMode::grid) {
        f.unit = grid_unit(grid.s, img.width, img.height);
        f.tile = grid_tile_size(grid.s);
        f.margin = aa.filter == AaFilter::tent ? 1 : 0;
    } else if (aa.mode == AaMode::adaptive) {
        f.tile = kSamplerTile;
        f.margin = 1;  // corners on a tile's right and bottom borders
    }
    f.tiles_x = (img.width + f.tile - 1) / f.tile;
    f.tiles_y = (img.height + f.tile - 1) / f.tile;
    if (control.aa_mask) {
        control.aa_mask->width = img.width;
        control.aa_mask->height = img.height;
        control.aa_mask->level.assign(static_cast<size_t>(img.width) * img.height, 0);
    }

    // 1. Project every vertex.
    const auto& positions = geometry.mesh.positions;
    f.vertices.resize(positions.size());
    const size_t vertex_chunks = (positions.size() + kChunkSize - 1) / kChunkSize;
    parallel_items(control.threads, vertex_chunks, [&](size_t c) {
        const size_t end = std::min(positions.size(), (c + 1) * kChunkSize);
        for (size_t i = c * kChunkSize; i < end; ++i)
            f.vertices[i] = project(f.camera, f.perspective, positions[i]);
    });

    // 2. Clip and bin triangles, chunk by chunk (chunk boundaries fixed: same bins always).
    const size_t triangles = geometry.mesh.triangle_count();
    std::vector<ChunkBins> chunks((triangles + kChunkSize - 1) / kChunkSize);
    parallel_items(control.threads, chunks.size(), [&](size_t c) {
        bin_chunk(f, c * kChunkSize, std::min(triangles, (c + 1) * kChunkSize), chunks[c]);
    });
    for (const ChunkBins& c : chunks) stats.triangles += c.triangles.size();

    // 3. Rasterize and shade each tile: chunks in order, so ties resolve the same way always.
    const size_t tile_count = static_cast<size_t>(f.tiles_x) * f.tiles_y;
    const size_t items = aa.mode == AaMode::adaptive ? 2 * tile_count : tile_count;
    std::vector<RenderStats> tile_stats(items);
    std::atomic<size_t> tiles_done{0};
    const auto cancelled = [&] {
        return control.cancel && control.cancel->load(std::memory_order_relaxed);
    };
    const auto report = [&] {
        const size_t done = ++tiles_done;
        if (control.progress) control.progress(static_cast<double>(done) / items);
    };
    switch (aa.mode) {
        case AaMode::none:
            parallel_items(control.threads, tile_count, [&](size_t t) {
                if (cancelled()) return;
                const PixelRect r = tile_rect(f, t);
                Fragment frags[kTileSize * kTileSize];
                rasterize_bins(f, chunks, t, centres(f, r.x0, r.y0, r.width(), r.height()), frags);
                shade_tile(f, r.x0, r.y0, r.width(), r.height(), frags, out, tile_stats[t]);
                report();
            });
            break;
        case AaMode::grid:
            parallel_items(control.threads, tile_count, [&](size_t t) {
                if (cancelled()) return;
                grid_tile(f, chunks, t, grid, out, tile_stats[t]);
                report();
            });
            break;
        case AaMode::adaptive: {
            // Pass 1: every pixel corner (x, y integers), rasterized and shaded once.
            const int W = f.width, H = f.height;
            std::vector<Rgb> corners(static_cast<size_t>(W + 1) * (H + 1));
            parallel_items(control.threads, tile_count, [&](size_t t) {
                if (cancelled()) return;
                const PixelRect c = corner_rect(tile_rect(f, t), W, H);
                const Lattice lat{c.x0 * f.unit, c.y0 * f.unit, f.unit, c.width(), c.height()};
                std::vector<Fragment>& frags = fragment_scratch();
                frags.resize(static_cast<size_t>(lat.w) * lat.h);
                rasterize_bins(f, chunks, t, lat, frags.data());
                const Lighting lighting = lighting_of(settings);
                for (int y = 0; y < lat.h; ++y)
                    for (int x = 0; x < lat.w; ++x)
                        corners[static_cast<size_t>(c.y0 + y) * (W + 1) + c.x0 + x] =
                            shade_fragment(f, lighting, frags[static_cast<size_t>(y) * lat.w + x],
                                           tile_stats[t]);
                report();
            });
            // Pass 2: pixels whose corners differ are refined on their finest lattice.
            const AdaptiveSpec spec = AdaptiveSpec::from(aa, W, H);
            parallel_items(control.threads, tile_count, [&](size_t t) {
                if (cancelled()) return;
                RenderStats& ts = tile_stats[tile_count + t];
                const Lighting lighting = lighting_of(settings);
                const int S = spec.lattice();
                std::vector<Fragment>& frags = fragment_scratch();
                frags.resize(static_cast<size_t>(S + 1) * (S + 1));
                ZbufferFine fine{f, chunks, t, lighting, ts, S, frags.data()};
                SamplerCounts counts;
                refine_tile(spec, tile_rect(f, t), corners.data(), fine, out, control.aa_mask,
                            counts);
                ts.pixels_refined += counts.pixels_refined;
                report();
            });
            break;
        }
    }
    for (const RenderStats& s : tile_stats) stats.add_counters(s);
}

}  // namespace luz
