// The batch engine's packets are used where they pay (docs/ARCHITECTURE.md): on the SPD's
// balls, every packet of camera rays goes down the BVH as one, reflected rays going one way
// do too, and the shadow rays of camera hits go down as one packet. Only the speed would tell
// if they stopped; ray_tracer_test.cpp checks that they give the bits of one ray at a time.
#include <gtest/gtest.h>

#include <vector>

#include "render/batch_tracer.h"
#include "scene/scene_loader.h"

namespace luz {
namespace {

TEST(PacketUse, CameraRaysReflectedRaysAndShadowRaysGoDownTheBvhAsPackets) {
    const int w = 64, h = 64;
    SceneDesc d =
        load_scene(LUZ_SOURCE_DIR "/scenes/spd/balls.nff",
                   {{"image.width", std::to_string(w)}, {"image.height", std::to_string(h)}});
    const BuiltScene scene = build_scene(d);
    ASSERT_EQ(scene.root_leaf, 0u) << "balls' 7381 spheres make a BVH of many leaves";
    const Whitted tracer(scene, d, true);
    const BatchTracer batch(tracer);
    std::vector<float> xs, ys;
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            xs.push_back(x + 0.5f);
            ys.push_back(y + 0.5f);
        }
    }
    const int n = w * h;
    std::vector<Rgb> out(n);
    TraceCounters c;
    batch.samples(xs.data(), ys.data(), n, c, out.data());

    const uint64_t camera_packets = n / kMaxPacket;  // batches of 64: whole packets of 8
    EXPECT_EQ(c.primary, uint64_t(n));
    EXPECT_GT(c.reflection, uint64_t(n) / 4) << "the sphereflake reflects";
    // Every camera packet (512), and packets of reflected rays: 45 here, those of neighbouring
    // points of the larger spheres.
    EXPECT_GT(c.tests.nearest_packets, camera_packets + 20);
    // Shadow rays of camera hits (the cache is empty at the first point of each packet).
    EXPECT_GT(c.tests.shadow_packets, camera_packets / 4);
    RecordProperty("nearest_packets", std::to_string(c.tests.nearest_packets));
    RecordProperty("shadow_packets", std::to_string(c.tests.shadow_packets));
}

}  // namespace
}  // namespace luz
