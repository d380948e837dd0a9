// The public API (include/luz/): build once, render with any settings; an edit rebuilds only
// what it needs; every front end's input goes through the one loader.
#include <gtest/gtest.h>

#include <cstring>
#include <nlohmann/json.hpp>
#include <thread>

#include "geometry/scene.h"  // build_scene(): the internal pipeline this compares with
#include "luz/json.h"
#include "luz/luz.h"
#include "luz/options.h"
#include "render/render.h"
#include "same_bits.h"

namespace luz {
namespace {

SceneDesc small(const std::string& demo, const char* pipeline) {
    return load_scene(demo, {{"image.width", "64"},
                             {"image.height", "48"},
                             {"render.pipeline", std::string("\"") + pipeline + "\""}});
}

/// The image a fresh build of `desc` renders.
Image fresh(const SceneDesc& desc) { return render(build(desc), desc).image; }

TEST(Api, RendersWhatTheInternalPipelineRenders) {
    const SceneDesc d = small("demo:whitted", "raytrace");
    const Frame f = render(build(d), d);
    EXPECT_TRUE(f.complete);
    EXPECT_EQ(f.image.width, 64);
    EXPECT_GT(f.stats.rays_shadow, 0u);
    RenderStats stats;
    EXPECT_TRUE(same_bits(f.image, render(build_scene(d), d, RenderControl{}, stats)));
}

TEST(Api, LightMaterialAndCameraEditsRebuildNothing) {
    EditableScene edit(small("demo:whitted", "raytrace"));
    Image before = render(edit.scene(), edit.desc()).image;
    EXPECT_EQ(edit.build_counts().geometry, 1);
    EXPECT_EQ(edit.build_counts().bvh, 1);

    // A light and a material: no geometry, no BVH rebuilt; the image is a fresh build's.
    edit.desc().lights[0].intensity = Rgb{0.3f, 0.6f, 0.9f};
    edit.desc().materials.back().kd = Rgb{0.9f, 0.1f, 0.1f};
    edit.desc().materials.back().transparency = 0.5f;  // shadow rays read it per render
    Image after = render(edit.scene(), edit.desc()).image;
    EXPECT_EQ(edit.build_counts().geometry, 1);
    EXPECT_EQ(edit.build_counts().bvh, 1);
    EXPECT_FALSE(same_bits(before, after));
    EXPECT_TRUE(same_bits(after, fresh(edit.desc())));

    // The camera, the model, the depth, the pipeline and the image size: nothing rebuilt.
    edit.desc().camera.position = Vec3{1, 4, 9};
    edit.desc().render.model = Model::lambert;
    edit.desc().render.max_depth = 2;
    edit.desc().image.width = 80;
    edit.desc().render.pipeline = Pipeline::zbuffer;
    after = render(edit.scene(), edit.desc()).image;
    edit.desc().render.pipeline = Pipeline::raycast;
    Image cast = render(edit.scene(), edit.desc()).image;
    EXPECT_EQ(edit.build_counts().geometry, 1);
    EXPECT_EQ(edit.build_counts().bvh, 1);
    EXPECT_TRUE(same_bits(after, fresh([&] {
                              SceneDesc z = edit.desc();
                              z.render.pipeline = Pipeline::zbuffer;
                              return z;
                          }())));
    EXPECT_TRUE(same_bits(cast, fresh(edit.desc())));

    // Tessellation and accel are geometry: one rebuild each (the BVH again when rays need it).
    edit.desc().geometry.tessellation = 12;
    (void)edit.scene();
    EXPECT_EQ(edit.build_counts().geometry, 2);
    edit.desc().geometry.accel = Accel::none;
    (void)render(edit.scene(), edit.desc());
    EXPECT_EQ(edit.build_counts().geometry, 3);
    EXPECT_EQ(edit.build_counts().bvh, 1);  // accel none builds no BVH
    // An object moved: a rebuild.
    edit.desc().objects[0].center.x += 0.5f;
    (void)edit.scene();
    EXPECT_EQ(edit.build_counts().geometry, 4);
}

TEST(Api, BvhIsBuiltOnceOnTheFirstRayTracedRender) {
    const SceneDesc d = small("demo:bunny", "zbuffer");
    const Scene scene = build(d);
    (void)render(scene, d);
    EXPECT_EQ(scene.build_counts().bvh, 0);  // a zbuffer render needs none
    Settings s = d;
    s.render.pipeline = Pipeline::raytrace;
    const Image a = render(scene, s).image;
    (void)render(scene, s);
    EXPECT_EQ(scene.build_counts().bvh, 1);
    EXPECT_EQ(scene.build_counts().geometry, 1);
    SceneDesc r = d;
    r.render.pipeline = Pipeline::raytrace;
    EXPECT_TRUE(same_bits(a, fresh(r)));
}

TEST(Api, ThreadsRenderOneSceneWithDifferentSettingsAtOnce) {
    const SceneDesc d = small("demo:bunny", "zbuffer");
    Settings ray = d;
    ray.render.pipeline = Pipeline::raytrace;
    ray.lights[0].intensity = Rgb{0.5f};
    const Scene scene = build(d);  // no BVH yet: the ray-traced render builds it meanwhile
    Frame zf, rf;
    std::thread a([&] { zf = render(scene, d); });
    std::thread b([&] { rf = render(scene, ray); });
    a.join();
    b.join();
    EXPECT_EQ(scene.build_counts().bvh, 1);
    EXPECT_EQ(zf.stats.bvh_nodes, 0u);  // a zbuffer render uses no BVH
    EXPECT_GT(rf.stats.bvh_nodes, 0u);
    EXPECT_TRUE(same_bits(zf.image, fresh(d)));
    SceneDesc r = d;
    static_cast<Settings&>(r) = ray;
    EXPECT_TRUE(same_bits(rf.image, fresh(r)));
}

TEST(Api, SettingsWithTooFewMaterialsAreRefused) {
    const SceneDesc d = small("demo:whitted", "raytrace");
    Settings s = d;
    s.materials.resize(1);
    try {
        (void)render(build(d), s);
        FAIL() << "no SceneError";
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("materials"), std::string::npos) << e.what();
    }
}

TEST(Api, ParsedJsonValueGoesThroughTheOneLoader) {
    const nlohmann::ordered_json value = {{"objects", {{{"type", "sphere"}, {"radius", 2}}}}};
    const SceneDesc d = load_scene_value(value, "<dict>", "");
    ASSERT_EQ(d.objects.size(), 1u);
    EXPECT_EQ(d.objects[0].radius, 2.0f);
    const SceneDesc text = parse_scene(value.dump(), "<dict>", "", {});
    EXPECT_TRUE(same_bits(fresh(d), fresh(text)));

    nlohmann::ordered_json bad = value;
    bad["objects"][0]["radius"] = -1;
    try {
        (void)load_scene_value(bad, "<dict>", "");
        FAIL() << "no SceneError";
    } catch (const SceneError& e) {
        EXPECT_STREQ(e.what(), "<dict>: objects.0.radius: must be > 0, got -1");
    }
    try {
        (void)load_scene_value(value, "<dict>", "", {parse_set("objects.0.radius=abc")});
        FAIL() << "no SceneError";
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("--set objects.0.radius=abc"), std::string::npos)
            << e.what();
    }
}

TEST(Api, WriteFrameGivesTheCliBytes) {
    const SceneDesc d = small("demo:primitives", "zbuffer");
    const Frame f = render(build(d), d);
    EXPECT_EQ(encode_frame(f, "x.png", d.image.encoding),
              encode_image("x.png", f.image, d.image.encoding));
    EXPECT_THROW(check_output_path("x.gif", "-o"), SceneError);
}

}  // namespace
}  // namespace luz
