// Tests of build_scene(): one shape per object, in order, with its material and object index.
#include "geometry/scene.h"

#include <gtest/gtest.h>

#include "geometry_fixtures.h"

namespace luz::test {
namespace {

TEST(BuildScene, OneShapePerObjectInOrder) {
    SceneDesc desc;
    desc.name = "three";
    desc.materials.resize(3);
    ObjectDesc a = sphere_desc(), b = plane_desc(), c = cone_desc();
    a.material = 2;
    b.material = 0;
    c.material = 1;
    desc.objects = {a, b, c};
    const BuiltScene scene = build_scene(desc);
    ASSERT_EQ(scene.shapes.size(), 3u);
    const ShapeType types[] = {ShapeType::sphere, ShapeType::plane, ShapeType::cone};
    const int materials[] = {2, 0, 1};
    for (int i = 0; i < 3; ++i) {
        EXPECT_EQ(scene.shapes[i].type, types[i]);
        EXPECT_EQ(scene.shapes[i].object, i);
        EXPECT_EQ(scene.shapes[i].material, materials[i]);
    }
    EXPECT_EQ(scene.shapes.size(), 3u);
    EXPECT_EQ(scene.material_count, 3u);
    // The shape is the one make_shape gives.
    const Vec3 expected = make_shape(c, 2).transform.point({0, 0, 1});
    EXPECT_EQ(scene.shapes[2].transform.point({0, 0, 1}), expected);
}

TEST(BuildScene, EmptySceneHasNoShapes) { EXPECT_TRUE(build_scene(SceneDesc{}).shapes.empty()); }

}  // namespace
}  // namespace luz::test
