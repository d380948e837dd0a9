// luz's public API for JSON values (e.g. a Python dict): a scene from a parsed value. Not part of
// luz/luz.h: the one public header that includes a library's (nlohmann/json_fwd.hpp).
#pragma once

#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "luz/scene_desc.h"

namespace luz {

/// Deepest nesting of arrays and objects a scene may have (a scene needs 5): deeper text or
/// values are refused before they are read.
inline constexpr int kMaxJsonNesting = 64;

/// load_scene() from a parsed JSON value; messages name `label` and key paths. Throws
/// SceneError.
SceneDesc load_scene_value(const nlohmann::ordered_json& value, const std::string& label,
                           const std::string& base_dir,
                           const std::vector<Override>& overrides = {});

}  // namespace luz
