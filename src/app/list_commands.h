// `luz scenes` and `luz materials`: the built-in scenes and the material presets.
#pragma once

#include <cstdio>

namespace luz {

/// One line per built-in scene: "demo:NAME  description".
void print_scenes(std::FILE* out);

/// A table of the presets: name, alias, ka, kd, ks, n, reflection, transparency, ior,
/// reflectance (constant or schlick, docs/SCENES.md#reflectance).
void print_materials(std::FILE* out);

}  // namespace luz
