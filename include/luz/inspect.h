// The ray-tree inspector (`luz view`'s click, luz.ray_tree, the web page): a pixel's ray tree,
// the same as JSON text with objects and materials named, and where a world point falls in the
// image (to draw the tree's rays over it).
#pragma once

#include <string>

#include "luz/ray_tree.h"
#include "luz/scene.h"

namespace luz {

/// The ray tree of the sample at pixel-space point (px, py) (the pixel's centre is
/// (i + 0.5, j + 0.5)): every ray traced for it with the numbers shade() and trace() used.
/// In the zbuffer pipeline, the primary hit traced as raycast.
RayTree ray_tree(const Scene& scene, const Settings& settings, float px, float py);

/// The ray tree of pixel (x, y) as JSON text (`luz view --click`, luz.ray_tree): the pixel, the
/// colour the render gave it, and every node with its terms, objects and materials named as in
/// the scene.
std::string ray_tree_json(const RayTree& tree, const SceneDesc& desc, int x, int y,
                          const Rgb& pixel);

/// Short names for the inspector: "objects.2 (sphere)", "material red", "lights.0".
std::string object_label(const SceneDesc& desc, int object);
std::string material_label(const SceneDesc& desc, int material);

/// Where world point `p` falls in the image of `settings`' camera, in pixel space (pixel (i, j)
/// covers [i, i+1) × [j, j+1)); false when it lies behind the camera plane (perspective).
bool project_point(const Settings& settings, const Vec3& p, float& px, float& py);

}  // namespace luz
