// Material presets of the lecture: Portuguese names with English aliases (SPEC §2).
#pragma once

#include <span>
#include <string_view>

#include "scene/material.h"

namespace luz {

struct Preset {
    std::string_view name;         ///< Portuguese, as in the lecture
    std::string_view alias;        ///< English
    std::string_view description;  ///< what it looks like, for `luz materials`
    Material material;
};

/// All eight presets, in the lecture's order.
std::span<const Preset> presets();

/// The preset called `name` (either name), or nullptr.
const Preset* find_preset(std::string_view name);

}  // namespace luz
