// render(): a runtime scene through the pipeline it names, to a float image.
#pragma once

#include <algorithm>
#include <atomic>
#include <functional>
#include <string>

#include "geometry/scene.h"
#include "image/image.h"
#include "render/stats.h"

namespace luz {

struct TermPlanes;
class Checkpoint;
class TileShare;

/// How a render is run: threads, progress reports and cancellation.
struct RenderControl {
    int threads = 0;  ///< 0: all cores
    /// Called now and then with the fraction done (0..1), from any one thread at a time.
    std::function<void(double)> progress;
    /// When set and true, the render stops early (the image is then incomplete).
    const std::atomic<bool>* cancel = nullptr;
    /// When set, receives which pixels adaptive antialiasing refined and how deeply
    /// (render/sampler.h; no pixel is refined in the other modes).
    AaMask* aa_mask = nullptr;
    /// When set, receives the per-term images it holds (docs/SCENES.md#terms), each the image's
    /// size.
    const TermPlanes* terms = nullptr;
    /// When set, called (from a render thread, any thread) with a warning about the render
    /// itself, each kind at most once per render: an exploding ray tree (render/ray_render.cpp),
    /// a --checkpoint that could not be written (render/work_items.h).
    std::function<void(const std::string&)> warning;
    /// When set, the ray pipelines keep finished tiles in it and skip those it already holds
    /// (render/checkpoint.h); the zbuffer renders every tile.
    Checkpoint* checkpoint = nullptr;
    /// When not empty, only the tiles that hold these pixels are rendered (--region, docs/CLI.md):
    /// its pixels are then those of the whole render, bit for bit; the image keeps the whole
    /// size and its other pixels are left as they were (the ray pipelines: unwritten).
    PixelRect region;
    /// When set, the work items are shared with other processes (MPI, render/tile_share.h):
    /// only those handed to this process are rendered here; on the process that gathers, the
    /// image is then the whole render's, on the others only their part of it.
    TileShare* share = nullptr;
};

/// Renders `scene` with `settings` (image, camera, pipeline, lights, materials …); fills
/// `stats`. The ray pipelines need the scene's BVH when its accel is bvh (build_bvh()).
Image render(const BuiltScene& scene, const Settings& settings, const RenderControl& control,
             RenderStats& stats);

/// Whether render_rows() can render this image band by band: the ray pipelines, each pixel
/// from its own samples (antialiasing none, or grid with the box filter), without terms, mask,
/// region, checkpoint or sharing.
bool renders_in_rows(const Settings& settings, const RenderControl& control);

/// render() of the image's rows y0 … y0 + count − 1 into rows 0 … count − 1 of `rows` (the
/// image's width, at least count rows): the very pixels render() gives there, so that a
/// caller can render a large image band by band into one small buffer (whose memory is
/// touched once, instead of a fresh image's: a first touch costs ~0.15 s of a core per 92 MB
/// on a VM) and encode each band as it is done (PngBands). Adds the band's counts to `stats`
/// (its sizes, threads and BVH figures set as render() sets them; not `seconds`). y0 and count
/// multiples of kSamplerTile (but for the image's last rows) keep every tile whole: then the
/// counts add up to the whole render's. Requires renders_in_rows().
void render_rows(const BuiltScene& scene, const Settings& settings, const RenderControl& control,
                 int y0, int count, Image& rows, RenderStats& stats);

}  // namespace luz
