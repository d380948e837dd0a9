// The zbuffer's preparation (every shape tessellated) stops with Cancelled once the calling
// thread's cancel flag is set (scene/cancel.h): a scene of thousands of spheres answers Ctrl-C
// before its first tile.
#include <gtest/gtest.h>

#include "geometry/scene.h"
#include "render/zbuffer.h"
#include "scene/cancel.h"

namespace luz {
namespace {

TEST(CancelZbuffer, ThePreparationStops) {
    SceneDesc desc;
    desc.geometry.accel = Accel::none;
    for (int i = 0; i < 100; ++i) {
        ObjectDesc o;
        o.center = Vec3{float(i), 0.0f, 0.0f};
        desc.objects.push_back(o);
    }
    const BuiltScene scene = build_scene(desc);
    std::atomic<bool> cancel{false};
    const CancelScope scope(&cancel);
    EXPECT_GT(prepare_zbuffer(scene, desc).mesh.indices.size(), 0u);
    cancel = true;
    EXPECT_THROW(prepare_zbuffer(scene, desc), Cancelled);
}

}  // namespace
}  // namespace luz
