// The ray tree recorded by Whitted::trace observed by a RayTreeRecorder: the same colour as the
// render, and terms that add up exactly as trace() and shade() added them.
#include "render/ray_tree.h"

#include <gtest/gtest.h>

#include "render/render.h"
#include "scene/scene_loader.h"

namespace luz {
namespace {

SceneDesc whitted(int w, int h) {
    return load_scene("demo:whitted",
                      {{"image.width", std::to_string(w)}, {"image.height", std::to_string(h)}});
}

void expect_adds_up(const RayTree& tree, int i) {
    const RayTreeNode& n = tree.nodes[i];
    if (n.hit != RayHit::object) return;
    // shade(): ambient + Σ (diffuse + specular), in the same order: the same bits.
    Rgb local = n.ambient;
    for (const LightTerm& l : n.lights) {
        if (l.visibility > 0 && l.cos_theta > 0) local += l.diffuse + l.specular;
    }
    EXPECT_EQ(local, n.local) << "node " << i;
    Rgb total = n.local;
    for (int j : {n.reflection_child, n.refraction_child}) {
        if (j < 0) continue;
        const RayTreeNode& c = tree.nodes[j];
        EXPECT_EQ(c.parent, i);
        EXPECT_EQ(c.returned, c.colour);
        EXPECT_NEAR(c.contribution.x, c.returned.x * c.A * c.coefficient, 1e-6f);
        total += c.contribution;
        expect_adds_up(tree, j);
    }
    EXPECT_EQ(total, n.colour) << "node " << i;
}

TEST(RayTreeRecording, PrimaryColourIsThePixelsAndTermsAddUp) {
    const SceneDesc d = whitted(64, 48);
    const BuiltScene scene = build_scene(d);
    RenderStats stats;
    const Image img = render(scene, d, RenderControl{}, stats);
    int with_children = 0;
    for (int y = 0; y < 48; y += 3) {
        for (int x = 0; x < 64; x += 3) {
            const RayTree tree = trace_ray_tree(scene, d, x + 0.5f, y + 0.5f);
            ASSERT_FALSE(tree.nodes.empty());
            EXPECT_EQ(tree.nodes[0].colour, img.at(x, y)) << x << "," << y;
            expect_adds_up(tree, 0);
            with_children += tree.nodes.size() > 1;
        }
    }
    EXPECT_GT(with_children, 10) << "mirror and glass pixels have secondary rays";
}

TEST(RayTreeRecording, RecordsGlassRefractionAndShadowVisibility) {
    const SceneDesc d = whitted(160, 120);
    const BuiltScene scene = build_scene(d);
    const RayTree tree = trace_ray_tree(scene, d, 98.5f, 70.5f);  // on the glass sphere
    ASSERT_GE(tree.nodes.size(), 3u);
    EXPECT_EQ(tree.nodes[0].hit, RayHit::object);
    EXPECT_GE(tree.nodes[0].refraction_child, 0);
    EXPECT_GE(tree.nodes[0].reflection_child, 0);
    EXPECT_EQ(tree.nodes[tree.nodes[0].refraction_child].kind, RayKind::refraction);
    EXPECT_EQ(tree.nodes[0].lights.size(), d.lights.size());
    EXPECT_FALSE(tree.raycast_for_zbuffer);
}

TEST(RayTreeRecording, ZbufferSceneIsTracedAsRaycast) {
    const SceneDesc d = load_scene("demo:primitives");
    const BuiltScene scene = build_scene(d);
    const RayTree tree = trace_ray_tree(scene, d, 400.5f, 300.5f);
    EXPECT_TRUE(tree.raycast_for_zbuffer);
    ASSERT_EQ(tree.nodes.size(), 1u) << "depth 0: no secondary rays";
    for (const LightTerm& l : tree.nodes[0].lights) EXPECT_EQ(l.visibility, 1.0f);
}

}  // namespace
}  // namespace luz
