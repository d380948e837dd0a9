// Animations (docs/SCENES.md#animation, docs/CLI.md#frames). A scene with an `animation` key is a
// sequence of frames, each a SceneDesc of its own (keyframed values set, the camera orbited); load
// once, every frame checked, then take the frames one by one.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "luz/render.h"
#include "luz/scene.h"
#include "luz/scene_text.h"

namespace luz {

/// A scene and its frames. Without an `animation` key, one frame: the scene itself.
class Animation {
  public:
    /// Loads `source` (a file or demo:NAME) as load_scene() does, with `overrides` applied
    /// before the keyframes; every frame is checked here. Throws SceneError.
    static Animation load(const std::string& source, const std::vector<Override>& overrides);

    /// N, the number of frames (1 for a scene without an animation).
    int frames() const { return first_.animation.frames > 0 ? first_.animation.frames : 1; }
    bool animated() const { return first_.animation.frames > 0; }
    double fps() const { return first_.animation.fps; }

    /// Frame 0.
    const SceneDesc& first() const { return first_; }
    /// Frame `f` (0 ≤ f < frames()); meshes are those read by load(). Throws SceneError.
    SceneDesc frame(int f) const;

  private:
    SceneText text_;
    std::vector<Override> overrides_;
    SceneDesc first_;
    struct Meshes;  ///< the OBJ files read (api/animation.cpp)
    std::shared_ptr<Meshes> meshes_;
};

/// Frames first … end−1.
struct FrameRange {
    int first = 0, end = 1;
    int count() const { return end - first; }
};

/// `--frames A:B` (0 ≤ A < B ≤ N) or `all`, for `animation`. Throws SceneError naming
/// `option` when the text is malformed, the range is empty or outside 0 … N, or the scene has
/// no animation.
FrameRange parse_frames(const std::string& text, const Animation& animation,
                        const std::string& option = "--frames");

/// The file of frame `f` for output `path`: X.EXT → X.0007.EXT (4 digits, more past 9999).
std::string frame_path(const std::string& path, int f);

/// `--stats` of a sequence of frames: the totals (counts and seconds summed, peak memory the
/// largest, the size and settings of the first frame) and `frames`, each frame's own
/// statistics with its number under `frame`. `stats[i]` is frame `numbers[i]` of `desc`.
std::string animation_stats_json(const std::vector<RenderStats>& stats,
                                 const std::vector<int>& numbers, const SceneDesc& desc);

}  // namespace luz
