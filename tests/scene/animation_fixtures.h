// Shared helpers of the animation tests: a frame of a scene text, a material by name, and a
// small scene with a given `animation` value (with those of scene_loader_fixtures.h).
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "scene/scene_loader.h"
#include "scene_loader_fixtures.h"

namespace luz::test {

inline SceneDesc frame_of(const std::string& json, int f,
                          const std::vector<Override>& overrides = {}, MeshCache* meshes = nullptr,
                          const std::string& base_dir = "scenes") {
    return parse_scene_frame(json, kFile, base_dir, overrides, f, meshes);
}

inline const Material& material(const SceneDesc& s, const std::string& name) {
    for (const Material& m : s.materials)
        if (m.name == name) return m;
    ADD_FAILURE() << "no material " << name;
    return s.materials.front();
}

/// A small scene with the `animation` value `animation`.
inline std::string scene_with(const std::string& animation) {
    return R"({"materials": {"red": {"kd": [0.8, 0.1, 0.1], "n": 10}},
               "lights": [{"position": [-4, 5, 5], "intensity": 10}],
               "objects": [{"type": "sphere", "material": "red"}],
               "animation": )" +
           animation + "}";
}

}  // namespace luz::test
