// luz's public API, part 2: rendering. render(scene, settings) → Frame: the float image, the
// per-term images asked for and the statistics.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "luz/image.h"
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
    /// the whole render (antialiasing and its filters included). render() checks it
    /// (check_region(), luz/options.h).
    std::optional<PixelRect> region;
};

/// Renders `scene` with `settings` (a SceneDesc is a Settings: pass it as it is, or an edited
/// copy). Builds the scene's BVH first if this is its first ray-traced render. Throws
/// SceneError when the settings do not fit the scene (fewer materials than its objects use).
Frame render(const Scene& scene, const Settings& settings, const RenderOptions& options = {});

/// The number of threads a render with `requested` threads uses (0: every core this process
/// may run on, as its CPU affinity allows).
int render_threads(int requested);

}  // namespace luz
