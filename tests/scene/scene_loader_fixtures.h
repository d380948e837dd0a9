// Shared helpers of the scene loader tests: parsing a scene text as scenes/a.json, --set
// arguments, and comparing vectors.
#pragma once

#include <gtest/gtest.h>

#include <initializer_list>
#include <string>
#include <vector>

#include "scene/scene_loader.h"

namespace luz::test {

inline SceneDesc parse(const std::string& json, const std::vector<Override>& overrides = {}) {
    return parse_scene(json, "scenes/a.json", "scenes", overrides);
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
