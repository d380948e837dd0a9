// Scene: the runtime scene built once from a SceneDesc; it never changes while rendering.
#pragma once

#include <vector>

#include "geometry/shape.h"
#include "scene/scene_desc.h"

namespace luz {

struct Scene {
    SceneDesc desc;               ///< settings, lights, materials
    std::vector<Shape> shapes;    ///< one per object, in the scene's order
    std::vector<Bounds3> bounds;  ///< world bounds of each shape (infinite for planes)
};

/// Builds the runtime scene from a validated description.
Scene build_scene(SceneDesc desc);

}  // namespace luz
