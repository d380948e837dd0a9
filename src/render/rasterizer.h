// The zbuffer's rasterizer: projects, clips and bins triangles into screen tiles, then finds the
// lattice points a tile's triangles cover and keeps the nearest: (triangle, barycentrics, depth)
// per point, for the pipeline to shade. It knows nothing of materials or shade().
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <mutex>
#include <vector>

#include "geometry/triangle_mesh.h"
#include "math/vec3.h"
#include "render/sampler.h"
#include "scene/camera.h"

namespace luz {

inline constexpr int kRasterTile = 64;      ///< pixels per tile side (no antialiasing)
inline constexpr int kSubpixelBits = 8;     ///< fixed-point precision of vertex positions
inline constexpr float kGuardBand = 16.0f;  ///< clip where |x| or |y| exceeds this many half-images
inline constexpr uint32_t kNoTriangle = std::numeric_limits<uint32_t>::max();

/// What the depth pass keeps per point: the nearest triangle and its barycentrics there.
struct Fragment {
    float depth;
    uint32_t triangle;  ///< index into the mesh's triangles, or kNoTriangle
    float b1, b2;       ///< perspective-correct barycentrics of vertices 1 and 2
};

/// The points a tile is rasterized at: point (a, b) at (x0 + a·step, y0 + b·step) in fixed
/// point, 0 ≤ a < w, 0 ≤ b < h; its fragment is frags[b·w + a]. Pixel centres, antialiasing
/// samples and pixel corners are all such lattices.
struct Lattice {
    int64_t x0, y0, step;
    int w, h;
};

/// How the image is cut up: fixed-point units per pixel, tile side, and the pixels a
/// triangle's box grows by when binned (for samples on tile borders).
struct RasterLayout {
    int64_t unit = int64_t{1} << kSubpixelBits;
    int tile = kRasterTile;
    int margin = 0;
};

/// A triangle ready to rasterize: fixed-point screen vertices, per-vertex depth and 1/w.
struct RasterTriangle {
    int32_t x[3], y[3];  ///< pixel coordinates · layout unit
    float depth[3];      ///< view depth (orthographic: interpolated linearly on screen)
    float inv_w[3];      ///< 1/w (perspective-correct interpolation; 1 when orthographic)
    uint32_t triangle;   ///< index of the original triangle
    int32_t clip;        ///< −1, or index of its vertices' barycentrics in ChunkBins::clip_bary
};

/// The tiles a binned triangle's box covers: [tx0, tx1] × [ty0, ty1].
struct TileSpan {
    int32_t tx0, tx1, ty0, ty1;
};

/// The triangles one chunk of the mesh sends to each tile, in triangle order: tile t's are
/// tile_triangles[tile_start[t] .. tile_start[t + 1]), indices into `triangles`.
struct ChunkBins {
    std::vector<RasterTriangle> triangles;
    std::vector<std::array<Vec3, 3>> clip_bary;
    std::vector<TileSpan> spans;  ///< per triangle: its tiles (binning's first pass)
    std::vector<uint32_t> tile_start;
    std::vector<uint32_t> tile_triangles;
};

/// A vertex in clip space: x, y in half-image units times w, depth along the view, w.
struct ClipVertex {
    float x, y, depth, w;
    Vec3 bary;  ///< barycentric coordinates in the original triangle
};

/// A frame's binning buffers, kept between frames so that the next frame of the same geometry
/// reuses their memory instead of allocating (and faulting in) it again.
struct RasterBuffers {
    std::vector<ClipVertex> vertices;
    std::vector<ChunkBins> chunks;
};

/// Where one frame leaves its buffers for the next (ZbufferGeometry holds one). Thread-safe: a
/// frame takes the spare buffers if there are any, else starts empty.
class RasterSpare {
  public:
    RasterBuffers take() {
        const std::lock_guard<std::mutex> lock(mutex_);
        return std::move(buffers_);
    }
    void give(RasterBuffers&& b) {
        const std::lock_guard<std::mutex> lock(mutex_);
        buffers_ = std::move(b);
    }

  private:
    std::mutex mutex_;
    RasterBuffers buffers_;
};

/// One frame's rasterizer: the mesh projected, clipped and binned once; then each tile
/// rasterized at any lattice, as often as asked.
class Rasterizer {
  public:
    /// Projects `mesh` through `camera` onto a width × height image, clips its triangles
    /// against the camera plane and a guard band and bins them into the tiles of `layout`
    /// (in parallel on `threads`; the same bins for any thread count). With `spare`, its
    /// buffers are reused and left there again for the next frame.
    Rasterizer(const TriangleMesh& mesh, const Camera& camera, int width, int height,
               const RasterLayout& layout, int threads, RasterSpare* spare = nullptr);
    ~Rasterizer();
    Rasterizer(const Rasterizer&) = delete;
    Rasterizer& operator=(const Rasterizer&) = delete;

    int width() const { return width_; }
    int height() const { return height_; }
    const RasterLayout& layout() const { return layout_; }
    size_t tile_count() const { return static_cast<size_t>(tiles_x_) * tiles_y_; }
    /// The pixels of tile `t` (row-major tile index).
    PixelRect tile_rect(size_t t) const {
        const int x0 = static_cast<int>(t % tiles_x_) * layout_.tile;
        const int y0 = static_cast<int>(t / tiles_x_) * layout_.tile;
        return {x0, y0, std::min(width_, x0 + layout_.tile), std::min(height_, y0 + layout_.tile)};
    }
    /// The lattice of the pixel centres of `r`.
    Lattice centres(const PixelRect& r) const {
        const int64_t u = layout_.unit;
        return {r.x0 * u + u / 2, r.y0 * u + u / 2, u, r.width(), r.height()};
    }
    /// Triangles set up and binned (a clipped triangle counts once per piece).
    uint64_t triangles() const;

    /// Rasterizes the triangles binned to tile `t` at the points of `lat` into `frags`
    /// (lat.w × lat.h): fixed-point edge functions, top-left rule (watertight, no point twice),
    /// nearest depth kept, ties to the earlier triangle. Points nothing covers get kNoTriangle.
    /// When `tests` is set (lat.w × lat.h), it receives each point's number of depth tests.
    void rasterize(size_t t, const Lattice& lat, Fragment* frags, uint32_t* tests = nullptr) const;

  private:
    bool perspective_;
    int width_, height_, tiles_x_, tiles_y_;
    RasterLayout layout_;
    RasterSpare* spare_;
    RasterBuffers buffers_;
    size_t chunk_count_ = 0;  ///< chunks of this frame (buffers_ may hold more)
};

}  // namespace luz
