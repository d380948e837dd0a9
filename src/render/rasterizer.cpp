// The zbuffer's rasterizer: vertices projected, triangles clipped (homogeneous Sutherland–Hodgman)
// and binned into tiles, then rasterized per tile with fixed-point edge functions and a depth test.
#include "render/rasterizer.h"

#include <algorithm>
#include <cmath>

#include "math/lane8.h"
#include "render/parallel.h"
#include "render/raster_kernels.h"

namespace luz {

namespace {

constexpr size_t kChunkSize = 16384;  // triangles per binning task (fixed: determinism)

/// What binning needs to know of the frame.
struct Binning {
    const TriangleMesh& mesh;
    const std::vector<ClipVertex>& vertices;  ///< projected mesh positions
    bool perspective;
    int width, height, tiles_x, tiles_y;
    int64_t unit;  ///< fixed-point units per pixel
    int tile;      ///< pixels per tile side
    int margin;    ///< pixels a triangle's box grows by when binned
};

/// std::lround(x) for |x| < 2^31, without the libm call: the integer part by truncation,
/// then the fraction x − trunc(x) (exact, by Sterbenz's lemma) decides; halves go away from 0.
int64_t round_half_away(double x) {
    int64_t i = static_cast<int64_t>(x);
    const double f = x - static_cast<double>(i);
    if (f >= 0.5) {
        ++i;
    } else if (f <= -0.5) {
        --i;
    }
    return i;
}

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
float near_depth(const Binning& f) { return f.perspective ? 1e-4f : 0.0f; }

/// Screen-space setup of a clipped or unclipped triangle; false if it covers no area.
bool setup(const Binning& f, const ClipVertex* v, uint32_t triangle, RasterTriangle& r) {
    const double sx = 0.5 * f.width * static_cast<double>(f.unit);
    const double sy = 0.5 * f.height * static_cast<double>(f.unit);
    for (int i = 0; i < 3; ++i) {
        const float iw = 1.0f / v[i].w;
        // px = (x+1)·W/2, py = (1−y)·H/2 (docs/SCENES.md#geometry), in fixed point.
        r.x[i] = static_cast<int32_t>(round_half_away((double{v[i].x} * iw + 1.0) * sx));
        r.y[i] = static_cast<int32_t>(round_half_away((1.0 - double{v[i].y} * iw) * sy));
        r.depth[i] = v[i].depth;
        r.inv_w[i] = iw;
    }
    r.triangle = triangle;
    r.clip = -1;
    const int64_t area = static_cast<int64_t>(r.x[1] - r.x[0]) * (r.y[2] - r.y[0]) -
                         static_cast<int64_t>(r.y[1] - r.y[0]) * (r.x[2] - r.x[0]);
    return area != 0;
}

/// Keeps a set-up triangle and the tiles its bounding box touches (binning's first pass),
/// counted in bins.tile_start[t + 1].
void bin(const Binning& f, ChunkBins& bins, const RasterTriangle& r) {
    const auto pixel = [&](int32_t v, int grow) {
        return static_cast<int32_t>(floor_div(v, f.unit)) + grow;
    };
    const int32_t lo_x = pixel(std::min({r.x[0], r.x[1], r.x[2]}), -f.margin);
    const int32_t hi_x = pixel(std::max({r.x[0], r.x[1], r.x[2]}), f.margin);
    const int32_t lo_y = pixel(std::min({r.y[0], r.y[1], r.y[2]}), -f.margin);
    const int32_t hi_y = pixel(std::max({r.y[0], r.y[1], r.y[2]}), f.margin);
    if (hi_x < 0 || hi_y < 0 || lo_x >= f.width || lo_y >= f.height) return;
    const TileSpan span{std::max(0, lo_x / f.tile), std::min(f.tiles_x - 1, hi_x / f.tile),
                        std::max(0, lo_y / f.tile), std::min(f.tiles_y - 1, hi_y / f.tile)};
    bins.triangles.push_back(r);
    bins.spans.push_back(span);
    for (int ty = span.ty0; ty <= span.ty1; ++ty)
        for (int tx = span.tx0; tx <= span.tx1; ++tx) ++bins.tile_start[ty * f.tiles_x + tx + 1];
}

/// Binning's second pass: every kept triangle's index into the lists of its tiles, in
/// triangle order (tile_start holds the counts, then the offsets).
void fill_tile_lists(const Binning& f, ChunkBins& bins) {
    const size_t tiles = bins.tile_start.size() - 1;
    for (size_t t = 0; t < tiles; ++t) bins.tile_start[t + 1] += bins.tile_start[t];
    bins.tile_triangles.resize(bins.tile_start[tiles]);
    thread_local std::vector<uint32_t> cursor;  // where tile t's next index goes
    cursor.assign(bins.tile_start.begin(), bins.tile_start.end() - 1);
    for (uint32_t index = 0; index < bins.spans.size(); ++index) {
        const TileSpan& s = bins.spans[index];
        for (int ty = s.ty0; ty <= s.ty1; ++ty)
            for (int tx = s.tx0; tx <= s.tx1; ++tx)
                bins.tile_triangles[cursor[ty * f.tiles_x + tx]++] = index;
    }
}

/// Projects, clips and bins triangles [begin, end) (the buffers of `bins` reused).
void bin_chunk(const Binning& f, size_t begin, size_t end, ChunkBins& bins) {
    const TriangleMesh& mesh = f.mesh;
    const float near = near_depth(f);
    bins.triangles.clear();
    bins.clip_bary.clear();
    bins.spans.clear();
    bins.tile_start.assign(static_cast<size_t>(f.tiles_x) * f.tiles_y + 1, 0);
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
    fill_tile_lists(f, bins);
}

constexpr Fragment kEmptyFragment{std::numeric_limits<float>::infinity(), kNoTriangle, 0, 0};

}  // namespace

Rasterizer::Rasterizer(const TriangleMesh& mesh, const Camera& camera, int width, int height,
                       const RasterLayout& layout, int threads, RasterSpare* spare)
    : perspective_(camera.projection == Projection::perspective),
      width_(width),
      height_(height),
      tiles_x_((width + layout.tile - 1) / layout.tile),
      tiles_y_((height + layout.tile - 1) / layout.tile),
      layout_(layout),
      spare_(spare) {
    if (spare_) buffers_ = spare_->take();
    // 1. Project every vertex.
    const auto& positions = mesh.positions;
    std::vector<ClipVertex>& vertices = buffers_.vertices;
    vertices.resize(positions.size());
    const size_t vertex_chunks = (positions.size() + kChunkSize - 1) / kChunkSize;
    parallel_items(threads, vertex_chunks, [&](size_t c) {
        const size_t end = std::min(positions.size(), (c + 1) * kChunkSize);
        for (size_t i = c * kChunkSize; i < end; ++i)
            vertices[i] = project(camera, perspective_, positions[i]);
    });

    // 2. Clip and bin triangles, chunk by chunk (chunk boundaries fixed: same bins always).
    const Binning f{mesh,     vertices, perspective_, width,       height,
                    tiles_x_, tiles_y_, layout.unit,  layout.tile, layout.margin};
    const size_t triangles = mesh.triangle_count();
    chunk_count_ = (triangles + kChunkSize - 1) / kChunkSize;
    if (buffers_.chunks.size() < chunk_count_) buffers_.chunks.resize(chunk_count_);
    parallel_items(threads, chunk_count_, [&](size_t c) {
        bin_chunk(f, c * kChunkSize, std::min(triangles, (c + 1) * kChunkSize), buffers_.chunks[c]);
    });
}

Rasterizer::~Rasterizer() {
    if (spare_) spare_->give(std::move(buffers_));
}

uint64_t Rasterizer::triangles() const {
    uint64_t n = 0;
    for (size_t c = 0; c < chunk_count_; ++c) n += buffers_.chunks[c].triangles.size();
    return n;
}

void Rasterizer::rasterize(size_t t, const Lattice& lat, Fragment* frags, uint32_t* tests) const {
    const size_t points = static_cast<size_t>(lat.w) * lat.h;
    std::fill(frags, frags + points, kEmptyFragment);
    if (tests) std::fill(tests, tests + points, 0u);
    // The lanes kernel's copy of the fragments' depths (and its 8 floats of padding).
    thread_local std::vector<float> depths;
    if (!tests) depths.assign(points + kPacketLanes, std::numeric_limits<float>::infinity());
    // Chunks in order, so that ties resolve the same way always.
    for (size_t k = 0; k < chunk_count_; ++k) {
        const ChunkBins& c = buffers_.chunks[k];
        for (uint32_t i = c.tile_start[t], end = c.tile_start[t + 1]; i < end; ++i) {
            const uint32_t index = c.tile_triangles[i];
            const RasterTriangle& r = c.triangles[index];
            const std::array<Vec3, 3>* clip_bary = r.clip >= 0 ? &c.clip_bary[r.clip] : nullptr;
            if (tests) {
                rasterize_triangle_reference(perspective_, r, clip_bary, lat, frags, tests);
            } else {
                rasterize_triangle_lanes(perspective_, r, clip_bary, lat, frags, depths.data());
            }
        }
    }
}

}  // namespace luz
