// luz.Scene: a loaded, built scene and what it was loaded from, so that a render with other
// options or `set=` overrides parses the same text again with them (exactly as `luz render`
// applies its options to the file) and reuses the built geometry when nothing it holds changed.
#pragma once

#include <pybind11/pybind11.h>

#include <memory>
#include <string>
#include <vector>

#include "luz/luz.h"
#include "luz/scene_text.h"

namespace luz::python {

/// A scene as luz.load() made it. Immutable once made: renders on several threads share it.
struct SceneHandle {
    SceneText source;                 ///< the JSON text, its label ("<dict>" for a dict), folder
    std::vector<Override> overrides;  ///< applied to the text, in order
    SceneDesc desc;                   ///< the validated description
    Scene scene;                      ///< built from desc (BVH on the first ray-traced render)
};

/// Shared by the Python object, the frames rendered from it and the scenes derived from it;
/// never changed after it is made.
using SceneRef = std::shared_ptr<SceneHandle>;

/// The overrides of a `set=` argument: a dict PATH → value, each value as JSON, applied like
/// `--set PATH=JSON` (origin "--set"), in the dict's order. None gives none. Throws TypeError.
std::vector<Override> set_overrides(pybind11::handle set);

/// Loads `source` — a path (str or os.PathLike), "demo:NAME", a dict, or a luz.Scene (then
/// `overrides` are added to its own) — with `overrides` applied after the source's own.
/// Parses and builds with the GIL released. Throws SceneError, TypeError.
SceneRef load_source(pybind11::handle source, const std::vector<Override>& overrides);

/// `base` with `extra` overrides added: its text parsed again with all of them; its built
/// geometry kept when the objects, tessellation and accel come out the same. `base` itself
/// when `extra` is empty. Call with the GIL released.
SceneRef derive(const SceneRef& base, const std::vector<Override>& extra);

/// Issues the description's warnings (a missing MTL file …) as luz.SceneWarning, skipping
/// those `already` issued. Call with the GIL held.
void warn(const SceneDesc& desc, const SceneDesc* already = nullptr);

/// The luz.SceneWarning class (set up by the module).
extern pybind11::handle scene_warning_type;

}  // namespace luz::python
