// Builds stop with Cancelled once the calling thread's cancel flag is set (scene/cancel.h): the
// scene's shapes, a mesh's transform and normals, and every task of the parallel BVH build look
// at it, so that Ctrl-C during the build of a large scene answers at once.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "geometry/bvh.h"
#include "geometry/mesh.h"
#include "geometry/scene.h"
#include "scene/cancel.h"

namespace luz {
namespace {

std::vector<Bounds3> random_boxes(int n) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.0f, 100.0f);
    std::vector<Bounds3> boxes;
    for (int i = 0; i < n; ++i) {
        const Vec3 p{u(rng), u(rng), u(rng)};
        boxes.push_back({p, p + Vec3{0.5f}});
    }
    return boxes;
}

TEST(CancelBuild, ABvhBuildStops) {
    const std::vector<Bounds3> boxes = random_boxes(200000);  // large nodes: parallel tasks
    std::atomic<bool> cancel{false};
    const CancelScope scope(&cancel);
    EXPECT_GT(Bvh::build(boxes).nodes().size(), 1u);
    cancel = true;
    EXPECT_THROW(Bvh::build(boxes), Cancelled);
    EXPECT_THROW(Bvh8::build(boxes), Cancelled);
}

TEST(CancelBuild, ASceneBuildStops) {
    auto mesh = std::make_shared<MeshData>();
    mesh->positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    mesh->position = {0, 1, 2};
    mesh->normal = {-1, -1, -1};
    mesh->material = {-1};
    SceneDesc desc;
    ObjectDesc o;
    o.type = ShapeType::mesh;
    o.mesh = mesh;
    o.smooth = true;
    desc.objects.push_back(o);
    std::atomic<bool> cancel{false};
    const CancelScope scope(&cancel);
    EXPECT_EQ(build_mesh(o).indices.size(), 3u);
    EXPECT_EQ(build_scene(desc).shapes.size(), 1u);
    cancel = true;
    EXPECT_THROW(build_mesh(o), Cancelled);
    EXPECT_THROW(build_scene(desc), Cancelled);
}

TEST(CancelBuild, AScenesBvhBuildStopsAndCanBeBuiltAgain) {
    // as Scene::prepare() builds it on the first ray-traced render, under its lock
    SceneDesc desc;
    desc.geometry.accel = Accel::none;
    for (int i = 0; i < 5000; ++i) {
        ObjectDesc o;
        o.center = Vec3{float(i % 50), float(i / 50), 0.0f};
        o.radius = 0.3f;
        desc.objects.push_back(o);
    }
    BuiltScene scene = build_scene(desc);
    const BuiltScene whole = [&] {
        BuiltScene s = build_scene(desc);
        build_bvh(s);
        return s;
    }();
    std::atomic<bool> cancel{true};
    const CancelScope scope(&cancel);
    EXPECT_THROW(build_bvh(scene), Cancelled);
    EXPECT_FALSE(scene.has_bvh);
    cancel = false;
    build_bvh(scene);
    EXPECT_TRUE(scene.has_bvh);
    EXPECT_EQ(scene.bvh.nodes().size(), whole.bvh.nodes().size());
    EXPECT_EQ(scene.bvh_blocks.size(), whole.bvh_blocks.size());
    EXPECT_EQ(scene.unbounded, whole.unbounded);
}

}  // namespace
}  // namespace luz
