// BuiltScene writer: a SceneDesc back to scene JSON (docs/SCENES.md#scene-files) that the loader
// reads into the same description — every key written, materials by name, mesh paths relative to
// the new file.
#pragma once

#include <string>

#include "scene/scene_desc.h"

namespace luz {

/// The scene as JSON text. Mesh files are written relative to `out_dir` (the folder of the
/// file the text goes to) when they lie on disk, else as they are. MTL materials are not
/// written: a mesh without a `material` reads them again from its MTL file.
std::string scene_to_json(const SceneDesc& desc, const std::string& out_dir);

/// Writes scene_to_json to `path` (temporary file renamed into place). A built-in scene's
/// embedded mesh (e.g. demo:bunny's bunny.obj) is written next to it when no such file exists
/// there. Throws std::runtime_error naming the file on failure.
void write_scene(const std::string& path, const SceneDesc& desc);

}  // namespace luz
