// `--set PATH=JSON` overrides (and command-line options turned into them): parsing and
// applying them to the scene document before it is read.
#pragma once

#include <string>

#include "scene/json_text.h"
#include "scene/scene_loader.h"

namespace luz::loader {

/// How messages name the override: "--set PATH=JSON", or e.g. "--width 800".
std::string override_label(const Override& o);

/// Sets the value at the override's dotted path in `doc`. A numeric segment indexes an array
/// (index == size appends a new element), a missing object key is created (as an array when
/// the next segment is an index, else as an object). Returns the shallowest key path the
/// override created or replaced: errors found under it are the override's. Throws InputError.
std::string apply_override(Json& doc, const Override& o);

}  // namespace luz::loader
