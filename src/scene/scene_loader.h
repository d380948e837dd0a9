// BuiltScene loading: JSON text (a file or a built-in demo) plus overrides → validated SceneDesc.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "scene/input_error.h"
#include "scene/scene_desc.h"

namespace luz {

/// Parses "PATH=JSON" as given to --set; throws InputError when malformed.
Override parse_set(const std::string& arg);

/// Reads `source` — a file path or "demo:NAME" — without parsing it: parse_scene(text, label,
/// base_dir, overrides) then gives what load_scene(source, overrides) gives. Throws InputError
/// for an unknown demo or an unreadable file.
SceneText read_scene_text(const std::string& source);

/// Loads `source` — a file path or "demo:NAME" — applies the overrides in order and validates
/// the result (docs/SCENES.md#scene-files). Throws InputError naming the file and the line:column
/// or key path.
SceneDesc load_scene(const std::string& source, const std::vector<Override>& overrides = {});

/// The same from JSON text; `file` labels messages and `base_dir` resolves relative paths. A
/// scene with an `animation` gives its frame 0, with every frame checked
/// (docs/SCENES.md#scene-files). Meshes in `meshes` are reused, and those read are added to it
/// (nullptr: none).
SceneDesc parse_scene(std::string_view json_text, const std::string& file,
                      const std::string& base_dir, const std::vector<Override>& overrides = {});
SceneDesc parse_scene(std::string_view json_text, const std::string& file,
                      const std::string& base_dir, const std::vector<Override>& overrides,
                      MeshCache* meshes);

/// Frame `frame` of the scene's animation (frame 0 of a scene without one): its keyframed values
/// set after `overrides`, then the camera's orbit. Meshes in `meshes` are reused, and those read
/// are added to it (nullptr: none). Checks only this frame. Throws InputError.
SceneDesc parse_scene_frame(std::string_view json_text, const std::string& file,
                            const std::string& base_dir, const std::vector<Override>& overrides,
                            int frame, MeshCache* meshes);

}  // namespace luz
