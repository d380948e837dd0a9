// Material presets of the lecture and three metals: Portuguese names with English aliases
// (docs/SCENES.md#scene-files, #reflectance).
#pragma once

#include <span>
#include <string_view>

#include "luz/material.h"

namespace luz {

struct Preset {
    std::string_view name;         ///< Portuguese, as in the lecture
    std::string_view alias;        ///< English
    std::string_view description;  ///< what it looks like, for `luz materials`
    Material material;
};

/// All eleven presets: the lecture's eight in its order, then ouro, prata and cobre.
std::span<const Preset> presets();

/// The preset called `name` (either name), or nullptr.
const Preset* find_preset(std::string_view name);

}  // namespace luz
