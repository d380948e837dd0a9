// Built-in scenes, named demo:NAME wherever a scene path is accepted (docs/SCENES.md#scene-files).
#pragma once

#include <span>
#include <string_view>

namespace luz {

struct DemoScene {
    std::string_view name;         ///< without the "demo:" prefix
    std::string_view description;  ///< one line, for `luz scenes`
    std::string_view json;         ///< the scene file's text
};

std::span<const DemoScene> demo_scenes();

/// The demo called `name` (without "demo:"), or nullptr.
const DemoScene* find_demo(std::string_view name);

}  // namespace luz
