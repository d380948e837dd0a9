// The runtime scene a public luz::Scene holds (geometry/scene.h): for the API's own files and the
// tests, never for a front end.
#pragma once

#include "geometry/scene.h"
#include "luz/scene.h"

namespace luz {

/// The runtime scene of `scene` (shapes, meshes, BVH once prepared). Throws std::logic_error
/// before build().
const BuiltScene& built_scene(const Scene& scene);

}  // namespace luz
