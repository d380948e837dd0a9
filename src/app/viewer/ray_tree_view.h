// The ray-tree inspector: a clicked pixel's tree as text in the panel and as rays drawn over
// the image.
#pragma once

#include <imgui.h>

#include "luz/inspect.h"
#include "luz/luz.h"

namespace luz {

/// Writes the tree into the current ImGui window: per node the object, distance, ambient,
/// each light's diffuse, specular and visibility, the children's weights and contributions,
/// and how they add up to the pixel's colour `pixel`.
void draw_ray_tree_panel(const RayTree& tree, const SceneDesc& desc, int x, int y,
                         const Rgb& pixel);

/// Draws the tree's rays (and shadow rays to the lights) over the image shown at `origin` with
/// `scale` screen pixels per image pixel.
void draw_ray_tree_overlay(ImDrawList* draw, const RayTree& tree, const SceneDesc& desc,
                           ImVec2 origin, float scale, int x, int y);

}  // namespace luz
