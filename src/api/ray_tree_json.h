// The ray tree of a clicked pixel as JSON (`luz view --click`), for tests and scripts.
#pragma once

#include <string>

#include "render/ray_tree.h"
#include "scene/scene_desc.h"

namespace luz {

/// The tree of pixel (x, y) as JSON text: the pixel, the colour the render gave it, and every
/// node with its terms (render/ray_tree.h), objects and materials named as in the scene.
std::string ray_tree_json(const RayTree& tree, const SceneDesc& desc, int x, int y,
                          const Rgb& pixel);

/// Short names for the inspector: "objects.2 (sphere)", "material red", "lights.0".
std::string object_label(const SceneDesc& desc, int object);
std::string material_label(const SceneDesc& desc, int material);

}  // namespace luz
