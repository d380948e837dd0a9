// The memory check before rendering (luz/memory.h): the zbuffer's tessellation is counted by each
// shape's own triangles, so that a scene of many open cylinders (the SPD tree's branches) is not
// refused for triangles it would never make.
#include "luz/memory.h"

#include <gtest/gtest.h>

#include <string>

#include "luz/errors.h"
#include "luz/scene.h"

namespace luz {
namespace {

/// `n` open cylinders (an SPD tree's branches, without caps) rendered by the zbuffer at
/// tessellation t: 2t triangles each.
SceneDesc cylinders(int n, int t) {
    std::string objects;
    for (int i = 0; i < n; ++i) {
        objects += std::string(i ? "," : "") +
                   R"({"type": "cylinder", "base": [0, 0, 0], "axis": [0, 1, 0], "radius": 0.1,
                       "height": 1, "caps": false})";
    }
    const std::string json = R"({"render": {"pipeline": "zbuffer", "tessellation": )" +
                             std::to_string(t) + R"(}, "image": {"width": 64, "height": 64},
                             "objects": [)" +
                             objects + "]}";
    return parse_scene(json, "cylinders.json", ".", {});
}

TEST(Memory, TessellationCountsEachShapesOwnTriangles) {
    // 2000 × 2·512 triangles × 160 bytes ≈ 330 MB (2·t² a shape would be ≈ 170 GB)
    const SceneDesc d = cylinders(2000, 512);
    EXPECT_NO_THROW(check_memory(d, uint64_t{1} << 30));
    try {
        check_memory(d, uint64_t{256} << 20);
        ADD_FAILURE() << "not refused under 256 MiB";
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("render.tessellation"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace luz
