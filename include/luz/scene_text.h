// A scene as text and back: a scene file's text read without parsing (to parse it again with other
// overrides, as Python's Scene does), and a description written as JSON (scene_to_json,
// write_scene).
#pragma once

#include <string>

#include "luz/scene_desc.h"

namespace luz {

/// A scene's JSON text as load_scene() reads it, with how messages name it and the folder its
/// relative paths start from.
struct SceneText {
    std::string text;
    std::string label;     ///< the file path as given, or "demo:NAME"
    std::string base_dir;  ///< the file's folder ("" for a built-in scene)
};

/// Reads `source` — a file path or "demo:NAME" — without parsing it, so that a front end can
/// parse it again later with other overrides: parse_scene(text, label, base_dir, overrides)
/// gives what load_scene(source, overrides) gives. Throws SceneError.
SceneText read_scene_text(const std::string& source);

/// Writes `desc` back as a scene file (JSON, atomically); mesh paths relative to its folder.
void write_scene(const std::string& path, const SceneDesc& desc);

/// Lets `desc` share `base`'s loaded meshes where they came out the same (a reload of the same
/// OBJ file, e.g. for other overrides), so that needs_rebuild(), which compares meshes by
/// identity, sees equal objects as equal.
void share_meshes(const SceneDesc& base, SceneDesc& desc);

/// The scene as JSON text as the loader understood it (mesh paths relative to `out_dir`).
std::string scene_to_json(const SceneDesc& desc, const std::string& out_dir);

}  // namespace luz
