// render.min_weight (docs/SCENES.md#scene-files, POV-Ray's adc_bailout): a secondary ray whose
// weight — the product of the reflection and transparency coefficients on its path — is below it is
// not traced; checked against hand-traced trees. And the recorded ray tree's cap on an exploding
// pixel.
#include <gtest/gtest.h>

#include <cstring>
#include <functional>

#include "luz/inspect.h"
#include "luz/luz.h"
#include "same_bits.h"

namespace luz {
namespace {

/// Two mirrors facing each other (every reflection coefficient 0.5) and a mirror sphere.
SceneDesc mirrors(std::vector<Override> o) {
    const char* json = R"({
      "image": {"width": 40, "height": 30},
      "camera": {"projection": "perspective", "position": [0, 1, 4], "look_at": [0, 1, 0]},
      "render": {"pipeline": "raytrace", "max_depth": 12},
      "materials": {"m": {"kd": 0.3, "reflection": 0.5}},
      "objects": [
        {"type": "plane", "point": [0, 0, -2], "normal": [0, 0, 1], "material": "m"},
        {"type": "plane", "point": [0, 0, 6], "normal": [0, 0, -1], "material": "m"},
        {"type": "sphere", "center": [0.8, 1, 0], "radius": 0.5, "material": "m"}]})";
    return parse_scene(json, "mirrors.json", ".", o);
}

TEST(MinWeight, CutsTheTreeWhereTheWeightFallsBelowIt) {
    // Every coefficient is 0.5: a ray at depth k weighs 0.5^k. min_weight 0.3 keeps depth 1
    // (0.5) and drops depth 2 (0.25): the same tree, and so the same bits, as max_depth 1.
    const auto image = [](std::vector<Override> o) {
        const SceneDesc d = mirrors(o);
        return render(build(d), d);
    };
    const Frame cut = image({{"render.min_weight", "0.3"}});
    const Frame depth1 = image({{"render.max_depth", "1"}});
    EXPECT_TRUE(same_bits(cut.image, depth1.image));
    EXPECT_EQ(cut.stats.rays_reflection, depth1.stats.rays_reflection);
    // 0.2 keeps 0.25 (depth 2) and drops 0.125 (depth 3).
    EXPECT_TRUE(same_bits(image({{"render.min_weight", "0.2"}}).image,
                          image({{"render.max_depth", "2"}}).image));
    // Exactly at the weight: kept (only weights below it are cut).
    EXPECT_TRUE(same_bits(image({{"render.min_weight", "0.25"}}).image,
                          image({{"render.max_depth", "2"}}).image));
    // 0 traces the whole tree (docs/SCENES.md#ray-tracing).
    const Frame full = image({});
    EXPECT_GT(full.stats.rays_reflection, depth1.stats.rays_reflection * 2);
    EXPECT_TRUE(same_bits(full.image, image({{"render.min_weight", "0"}}).image));
}

TEST(MinWeight, EveryNodeOfARecordedTreeWeighsAtLeastMinWeightAndNoneIsMissing) {
    // Glass (reflection 0.1, transparency 0.9) inside glass: weights 0.9^a · 0.1^b.
    const char* json = R"({
      "image": {"width": 20, "height": 20},
      "camera": {"projection": "perspective", "position": [0, 0, 5], "look_at": [0, 0, 0]},
      "render": {"pipeline": "raytrace", "max_depth": 12, "min_weight": 0.7},
      "materials": {"g": {"preset": "vidro", "reflection": 0.1, "transparency": 0.9}},
      "objects": [{"type": "box", "min": [-1.5, -1.5, -1.5], "max": [1.5, 1.5, 1.5], "material": "g"},
                  {"type": "sphere", "radius": 1, "material": "g"}]})";
    const SceneDesc d = parse_scene(json, "glass.json", ".", {});
    const Scene scene = build(d);
    const RayTree tree = ray_tree(scene, d, 10.3f, 10.4f);
    ASSERT_GT(tree.nodes.size(), 3u);
    std::function<float(int)> weight = [&](int k) {
        const RayTreeNode& n = tree.nodes[k];
        return n.parent < 0 ? 1.0f : weight(n.parent) * n.coefficient;
    };
    int deepest = 0;
    for (int k = 0; k < static_cast<int>(tree.nodes.size()); ++k) {
        const RayTreeNode& n = tree.nodes[k];
        deepest = std::max(deepest, n.depth);
        const float w = weight(k);
        EXPECT_GE(w, 0.7f) << "node " << k;
        if (n.hit != RayHit::object || n.depth >= 12) continue;
        // Its children exist exactly when they weigh enough (by hand: w·0.1, w·0.9).
        EXPECT_EQ(n.reflection_child >= 0, w * 0.1f >= 0.7f) << "node " << k;
        EXPECT_EQ(n.refraction_child >= 0, w * 0.9f >= 0.7f) << "node " << k;
    }
    // 0.9³ = 0.729 ≥ 0.7 > 0.9⁴ = 0.656: the refraction chain stops at depth 3 (the ray would
    // go on through the sphere's far side and the box's).
    EXPECT_EQ(deepest, 3);
}

TEST(MinWeight, BadValuesAreRefusedWithTheKeyPath) {
    EXPECT_THROW(mirrors({{"render.min_weight", "-0.1"}}), SceneError);
    EXPECT_THROW(mirrors({{"render.min_weight", "1.01"}}), SceneError);
    try {
        mirrors({{"render.min_weight", "\"a lot\""}});
        FAIL();
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("render.min_weight"), std::string::npos) << e.what();
    }
}

TEST(RayTreeCap, AnExplodingPixelIsRecordedUpToTheCapWithItsExactColour) {
    SceneDesc d =
        load_scene(LUZ_SOURCE_DIR "/scenes/exploding_glass.json",
                   {{"image.width", "32"}, {"image.height", "24"}, {"render.max_depth", "16"}});
    const Scene scene = build(d);
    const RayTree tree = ray_tree(scene, d, 16.5f, 12.5f);
    EXPECT_TRUE(tree.truncated);
    EXPECT_EQ(tree.nodes.size(), kRayTreeMaxNodes);
    // The colour is traced in full all the same: the render's pixel, bit for bit.
    const Frame f = render(scene, d);
    EXPECT_EQ(std::memcmp(&tree.nodes[0].colour, &f.image.at(16, 12), sizeof(Rgb)), 0);
    // A small tree is not cut.
    const SceneDesc m = mirrors({});
    EXPECT_FALSE(ray_tree(build(m), m, 20.5f, 15.5f).truncated);
}

}  // namespace
}  // namespace luz
