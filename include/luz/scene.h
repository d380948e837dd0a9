// luz's public API, part 1: scenes. Load a description (a file, demo:NAME, JSON text or a
// parsed JSON value, with --set-style overrides), then build it once into a Scene.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "luz/demo_scenes.h"  // demo_scenes(): the built-in scenes (`luz scenes`)
#include "luz/errors.h"
#include "luz/presets.h"  // presets(): the material presets (`luz materials`)
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

/// Reads `source` — a file path or "demo:NAME" — without parsing it, so that a front end can
/// parse it again later with other overrides: parse_scene(text, label, base_dir, overrides)
/// gives what load_scene(source, overrides) gives. Throws SceneError.
SceneText read_scene_text(const std::string& source);

/// Writes `desc` back as a scene file (JSON, atomically); mesh paths relative to its folder.
void write_scene(const std::string& path, const SceneDesc& desc);

/// The cap on what loading a scene may use (its text, OBJ files, meshes), in bytes.
void set_memory_limit(uint64_t bytes);

/// The scene keys a front end's render options set (docs/CLI.md `--pipeline` … `--threshold`,
/// docs/PYTHON.md the Python keywords of the same names), each as the user gave it: a number's text
/// or a word; an unset one keeps the scene's value.
struct SceneOptions {
    std::optional<std::string> pipeline, model, width, height, max_depth, aa, samples, threshold;
};

/// The overrides that set those keys (render.pipeline, render.model, image.width,
/// image.height, render.max_depth, render.antialias.mode, .samples, .threshold), in that order,
/// each named after its command-line option ("--width 800") so that the loader checks and
/// reports them like the keys themselves: numbers go as typed, words as JSON strings.
std::vector<Override> option_overrides(const SceneOptions& options);

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

/// Lets `desc` share `base`'s loaded meshes where they came out the same (a reload of the same
/// OBJ file, e.g. for other overrides), so that needs_rebuild(), which compares meshes by
/// identity, sees equal objects as equal.
void share_meshes(const SceneDesc& base, SceneDesc& desc);

/// The range a slider of the scene key `key` (e.g. "render.max_depth", "materials.*.n") shows:
/// within the loader's limits for that key.
struct SliderRange {
    double lo, hi;
    bool capped = false;  ///< the key has an upper limit: a typed-in value stays ≤ hi
};
SliderRange slider_range(std::string_view key);

/// A numeric scene key that has a slider: its path ("lights.*.radius", "objects.sphere.radius")
/// and whether it takes whole numbers.
struct SliderKey {
    std::string key;
    bool integer = false;
};
/// Every numeric scene key with a range, in the loader's order (the web page's panel).
std::vector<SliderKey> slider_keys();

/// The scene as JSON text as the loader understood it (mesh paths relative to `out_dir`).
std::string scene_to_json(const SceneDesc& desc, const std::string& out_dir);

}  // namespace luz
