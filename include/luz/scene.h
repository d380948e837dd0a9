// luz's public API, part 1: scenes. Load a description (a file, demo:NAME, JSON text or a
// parsed JSON value, with --set-style overrides), then build it once into a Scene.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "luz/errors.h"
#include "luz/scene_desc.h"

namespace luz {

/// Loads `source` — a scene file or "demo:NAME" — and applies `overrides` in order (as
/// `--set PATH=JSON` does), validated once (docs/SCENES.md#scene-files). Throws SceneError.
SceneDesc load_scene(const std::string& source, const std::vector<Override>& overrides);

/// The same from JSON text: `label` names it in messages, `base_dir` resolves mesh paths.
SceneDesc parse_scene(std::string_view json_text, const std::string& label,
                      const std::string& base_dir, const std::vector<Override>& overrides);

/// `message` as one line, as every front end shows an error: trailing newlines dropped, inner
/// ones made spaces, other control bytes (quoted from a bad file) shown as '?'.
std::string one_line(const std::string& message);

/// Parses one "PATH=JSON" as given to --set. Throws SceneError when malformed.
Override parse_set(const std::string& arg);

/// How often a Scene's parts were built: a test of "edits rebuild nothing they need not".
struct BuildCounts {
    int geometry = 0;  ///< shapes placed, meshes transformed (build())
    int bvh = 0;       ///< BVH builds (the first ray-pipeline render with accel bvh)
};

/// A scene built for rendering: its shapes, meshes and (once a ray pipeline needs it) BVH.
/// Cheap to copy (shared and immutable); any number of threads may render it at once with
/// different Settings. What needs a build is the description's objects and `geometry`
/// (tessellation, accel); everything in Settings may change from one render to the next.
class Scene {
  public:
    Scene() = default;

    /// True once built.
    explicit operator bool() const { return state_ != nullptr; }

    /// How often its parts were built so far.
    BuildCounts build_counts() const;

    /// Builds the BVH now if `pipeline` traces rays with it and it is not built yet (render()
    /// does this itself; thread-safe).
    void prepare(Pipeline pipeline) const;

    /// Number of materials the objects refer to: a render's Settings must have at least these.
    size_t material_count() const;

    struct State;  ///< shared by copies (api/scene.cpp): the runtime scene, its BVH

  private:
    friend Scene build(const SceneDesc& desc);
    friend const State& scene_state(const Scene& scene);
    std::shared_ptr<State> state_;
};

/// Builds the geometry of a validated description (its objects, tessellation and accel).
Scene build(const SceneDesc& desc);

/// True when `a` and `b` differ in what needs a build (objects, tessellation, accel), so that
/// a Scene built from `a` cannot render `b`'s settings as they are meant.
bool needs_rebuild(const SceneDesc& a, const SceneDesc& b);

/// The settings part of a description (a copy: edit it, render with it, no rebuild).
inline Settings settings_of(const SceneDesc& desc) { return desc; }

/// A scene being edited (the viewer, a notebook): its description, free to change, and the
/// Scene built from it, rebuilt by scene() only when an edit needs it (needs_rebuild()): a
/// light, material, camera or render-setting edit rebuilds nothing.
class EditableScene {
  public:
    explicit EditableScene(SceneDesc desc) : desc_(std::move(desc)) {}

    /// The description: edit it freely, then call scene().
    SceneDesc& desc() { return desc_; }
    const SceneDesc& desc() const { return desc_; }

    /// The Scene for the description as it is now (built or rebuilt here if needed).
    const Scene& scene();

    /// Builds so far, over every Scene this has built.
    BuildCounts build_counts() const;

  private:
    SceneDesc desc_;
    SceneDesc built_from_;  ///< the description scene_ was built from
    Scene scene_;
    BuildCounts retired_;  ///< builds of the scenes replaced so far
};

}  // namespace luz
