// luz's public API, part 2: rendering. render(scene, settings) → Frame: the float image, the
// per-term images asked for and the statistics; and a pixel's ray tree.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "luz/image.h"
#include "luz/ray_tree.h"
#include "luz/scene.h"
#include "luz/stats.h"
#include "luz/terms.h"

namespace luz {

/// A per-term image (docs/SCENES.md#terms): which term, its name (`ambient`, `diffuse`, … `tests`)
/// and its pixels, filtered with the colour's antialiasing weights. Colour terms and `normal` are
/// RGB; `depth` and `tests` are one value per pixel, held in all three channels of `image`.
struct Aov {
    AovKind kind = AovKind::ambient;
    std::string name;
    Image image;
    bool scalar() const { return aov_is_scalar(kind); }
};

/// What one render made: it owns its image, its per-term images and its statistics.
struct Frame {
    Image image;            ///< linear float RGB, unclamped, row 0 on top
    std::vector<Aov> aovs;  ///< the per-term images asked for, in the order asked
    RenderStats stats;      ///< what --stats writes
    AaMask aa_mask;         ///< which pixels adaptive antialiasing refined (when asked)
    bool complete = false;  ///< false when the render was cancelled (the image is then
                            ///< incomplete: write nothing)

    /// The per-term image called `name`, or nullptr when it was not asked for.
    const Aov* aov(std::string_view name) const {
        for (const Aov& a : aovs)
            if (a.name == name) return &a;
        return nullptr;
    }
};

/// What a library user sets for one render beyond the Settings.
struct RenderOptions {
    int threads = 0;  ///< 0: every core this process may run on
    /// Called now and then with the fraction done (0..1), from one thread at a time.
    std::function<void(double)> progress;
    /// When set and true, the render stops early (Frame::complete is then false).
    const std::atomic<bool>* cancel = nullptr;
    /// Called (from any render thread) with a warning about the render itself, each kind at
    /// most once per render (an exploding ray tree, a checkpoint that could not be written).
    std::function<void(const std::string&)> warning;
    bool want_aa_mask = false;  ///< fill Frame::aa_mask
    std::vector<AovKind> aovs;  ///< the per-term images to fill (parse_aov_list("all", …))
    /// When set, only these pixels (X1, Y1 exclusive; `--region`, docs/CLI.md): the Frame is
    /// region.width() × region.height(), its pixels bit for bit those of the same rectangle of
    /// the whole render (antialiasing and its filters included). render() checks it with
    /// check_region().
    std::optional<PixelRect> region;
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

/// What render_png() made: the PNG file's bytes (empty when cancelled) and the statistics.
struct PngFrame {
    std::string png;
    RenderStats stats;
    bool complete = false;
};

/// The image of render(scene, settings, options) as a PNG file with `encoding`, the very bytes
/// encode_frame() gives for it. Where it can (the ray pipelines, each pixel from its own
/// samples, no terms, mask or region asked for), it renders and compresses the image band by
/// band into one small buffer, without a float image of the whole size.
PngFrame render_png(const Scene& scene, const Settings& settings, const RenderOptions& options,
                    Encoding encoding);

/// The number of threads a render with `requested` threads uses (0: every core this process
/// may run on, as its CPU affinity allows).
int render_threads(int requested);

/// Where world point `p` falls in the image of `settings`' camera, in pixel space (pixel (i, j)
/// covers [i, i+1) × [j, j+1)); false when it lies behind the camera plane (perspective).
bool project_point(const Settings& settings, const Vec3& p, float& px, float& py);

/// Throws SceneError naming the scene and the key of the largest part (`image.width`,
/// `render.tessellation`, `objects.N.file`, `objects`) when rendering `desc` with `aov_count`
/// per-term images needs more than `limit` bytes (default: half the memory of this machine or
/// of its cgroup limit).
void check_memory(const SceneDesc& desc, std::optional<uint64_t> limit = std::nullopt,
                  int aov_count = 0);

/// Half of the physical memory (or of the cgroup limit, when smaller): check_memory()'s default
/// cap, and the one a front end gives set_memory_limit().
uint64_t default_memory_limit();

}  // namespace luz
