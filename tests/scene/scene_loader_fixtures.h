// Shared helpers of the scene loader and animation tests: parsing a scene text as scenes/a.json
// (with a mesh cache and a base directory), --set arguments, and comparing vectors.
#pragma once

#include <gtest/gtest.h>

#include <initializer_list>
#include <string>
#include <vector>

#include "scene/scene_loader.h"

namespace luz::test {

/// The label of the scenes parsed from text here: their messages start with it.
inline constexpr const char* kFile = "scenes/a.json";

inline SceneDesc parse(const std::string& json, const std::vector<Override>& overrides = {},
                       MeshCache* meshes = nullptr, const std::string& base_dir = "scenes") {
    return parse_scene(json, kFile, base_dir, overrides, meshes);
}

inline std::vector<Override> sets(std::initializer_list<const char*> args) {
    std::vector<Override> out;
    for (const char* a : args) out.push_back(parse_set(a));
    return out;
}

inline void expect_vec(const Vec3& a, const Vec3& b, float tol = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

}  // namespace luz::test
