// luz's public API, part 2: rendering. render(scene, settings) → Frame: the float image, the
// per-term images asked for and the statistics; and a pixel's ray tree.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "image/image.h"
#include "luz/scene.h"
#include "render/aov.h"         // AovKind, aov_name(), parse_aov_list(): the terms of SPEC §1.5
#include "render/checkpoint.h"  // Checkpoint: --checkpoint FILE
#include "render/parallel.h"    // resolve_threads()
#include "render/progress.h"    // ProgressBar: a terminal progress bar
#include "render/ray_tree.h"
#include "render/render.h"
#include "render/sampler.h"
#include "render/stats.h"
#include "scene/camera.h"  // Camera: rays and projection of SPEC §1.3

namespace luz {

/// A per-term image (SPEC §1.5): which term, its name (`ambient`, `diffuse`, … `tests`) and its
/// pixels, filtered with the colour's antialiasing weights. Colour terms and `normal` are RGB;
/// `depth` and `tests` are one value per pixel, held in all three channels of `image`.
struct Aov {
    AovKind kind = AovKind::ambient;
    std::string name;
    Image image;
    bool scalar() const { return aov_is_scalar(kind); }
};

/// What one render made.
struct Frame {
    Image image;            ///< linear float RGB, unclamped, row 0 on top
    std::vector<Aov> aovs;  ///< the per-term images asked for, in the order asked
    RenderStats stats;      ///< what --stats writes (api/stats_json.h)
    AaMask aa_mask;         ///< which pixels adaptive antialiasing refined (when asked)
    bool complete = false;  ///< false when the render was cancelled (the image is then
                            ///< incomplete: write nothing)
    /// The image as a PNG file, with `png_encoding`, when RenderOptions::png had it rendered
    /// straight into one (`image` is then empty, 0 × 0); empty otherwise.
    std::string png;
    Encoding png_encoding = Encoding::linear;

    /// The per-term image called `name`, or nullptr when it was not asked for.
    const Aov* aov(std::string_view name) const {
        for (const Aov& a : aovs)
            if (a.name == name) return &a;
        return nullptr;
    }
};

/// What a render needs beyond the settings: threads, progress, cancellation, the refinement
/// mask (render/render.h's RenderControl; `aa_mask` there is ignored: ask with `want_aa_mask`).
struct RenderOptions {
    RenderControl control;
    bool want_aa_mask = false;  ///< fill Frame::aa_mask
    std::vector<AovKind> aovs;  ///< the per-term images to fill (parse_aov_list("all", …))
    /// When set, only these pixels (X1, Y1 exclusive; `--region`, SPEC §3): the Frame is
    /// region.width() × region.height(), its pixels bit for bit those of the same rectangle of
    /// the whole render (antialiasing and its filters included). render() checks it with
    /// check_region().
    std::optional<PixelRect> region;
    /// When set, the image is wanted only as a PNG file with this encoding (as the CLI's
    /// `-o X.png`): render() may then render it band by band into one small buffer and
    /// compress each band as it is done (render_rows(), PngBands), so that no float image of
    /// the whole size is made — at 3200×2400 its 92 MB of fresh memory cost ~8 % of a
    /// Whitted render, on a VM. It does so when renders_in_rows() and nothing else is asked
    /// (no terms, mask or region): Frame::png then holds the file, the very bytes encode_image()
    /// gives for the whole image, and Frame::image stays empty. Otherwise the Frame is as
    /// without this option.
    std::optional<Encoding> png;
};

/// Throws SceneError naming `what` (e.g. "--region 0,0,900,10", "region") when `region` is
/// empty or not inside the `image`'s pixels.
void check_region(const PixelRect& region, const ImageDesc& image, const std::string& what);

/// Parses "X0,Y0,X1,Y1" (four integers) as given to --region; throws SceneError naming
/// `--region TEXT` when it is not four integers, empty, or outside `image`.
PixelRect parse_region(const std::string& text, const ImageDesc& image);

/// Renders `scene` with `settings` (a SceneDesc is a Settings: pass it as it is, or an edited
/// copy). Builds the scene's BVH first if this is its first ray-traced render. Throws
/// SceneError when the settings do not fit the scene (fewer materials than its objects use).
Frame render(const Scene& scene, const Settings& settings, const RenderOptions& options = {});

/// The ray tree of the sample at pixel-space point (px, py) (the pixel's centre is
/// (i + 0.5, j + 0.5)): every ray traced for it with the numbers shade() and trace() used.
/// In the zbuffer pipeline, the primary hit traced as raycast.
RayTree ray_tree(const Scene& scene, const Settings& settings, float px, float py);

}  // namespace luz
