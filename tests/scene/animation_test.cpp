// Tests of animations in the scene layer (docs/SCENES.md#scene-files `animation`): keyframes
// interpolated linearly and held, arrays, the camera's turntable orbit, keys set after --set,
// meshes read once over the frames.
#include "scene/animation.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "animation_fixtures.h"
#include "scene/scene_loader.h"

namespace luz {
namespace {

using test::expect_vec;
using test::frame_of;
using test::material;
using test::parse;
using test::scene_with;
using test::sets;
using ::testing::HasSubstr;

AnimationKey key(std::vector<int> frames, std::vector<std::vector<double>> values) {
    AnimationKey k;
    k.path = "materials.red.n";
    k.array = values.front().size() > 1;
    k.frames = std::move(frames);
    k.values = std::move(values);
    return k;
}

// --- key_value: the interpolation itself ---------------------------------------------------

TEST(AnimationKeyValue, LinearBetweenKeyframes) {
    const AnimationKey k = key({2, 6, 10}, {{1}, {9}, {5}});
    EXPECT_DOUBLE_EQ(key_value(k, 3)[0], 3.0);
    EXPECT_DOUBLE_EQ(key_value(k, 4)[0], 5.0);
    EXPECT_DOUBLE_EQ(key_value(k, 5)[0], 7.0);
    EXPECT_DOUBLE_EQ(key_value(k, 7)[0], 8.0);  // the second segment goes down
    EXPECT_DOUBLE_EQ(key_value(k, 9)[0], 6.0);
}

TEST(AnimationKeyValue, ExactlyTheKeyframeValuesAtKeyframes) {
    // Values whose interpolation would round: at the keyframe itself, the value as written.
    const AnimationKey k = key({0, 3, 7, 11}, {{0.1}, {0.7}, {1.0 / 3.0}, {1e-9}});
    for (std::size_t i = 0; i < k.frames.size(); ++i) {
        ASSERT_EQ(key_value(k, k.frames[i]).size(), 1u);
        EXPECT_EQ(key_value(k, k.frames[i])[0], k.values[i][0]) << "frame " << k.frames[i];
    }
}

TEST(AnimationKeyValue, HeldBeforeTheFirstAndAfterTheLast) {
    const AnimationKey k = key({4, 8}, {{2}, {6}});
    for (int f : {0, 1, 3, 4}) EXPECT_EQ(key_value(k, f)[0], 2.0) << f;
    for (int f : {8, 9, 100, 999999}) EXPECT_EQ(key_value(k, f)[0], 6.0) << f;
    // One keyframe: held everywhere.
    const AnimationKey one = key({5}, {{3}});
    for (int f : {0, 5, 6, 50}) EXPECT_EQ(key_value(one, f)[0], 3.0) << f;
}

TEST(AnimationKeyValue, ArraysInterpolateEachComponent) {
    const AnimationKey k = key({0, 4}, {{-4, 5, 1}, {4, 1, 1}});
    const std::vector<double> v = key_value(k, 1);
    ASSERT_EQ(v.size(), 3u);
    EXPECT_DOUBLE_EQ(v[0], -2.0);
    EXPECT_DOUBLE_EQ(v[1], 4.0);
    EXPECT_DOUBLE_EQ(v[2], 1.0);
    EXPECT_EQ(key_value(k, 0), k.values[0]);
    EXPECT_EQ(key_value(k, 7), k.values[1]);
}

TEST(AnimationKeyValue, FrameOverridesNameTheKeyAndTheFrame) {
    AnimationDesc a;
    a.frames = 8;
    a.keys.push_back(key({0, 4}, {{1}, {9}}));
    AnimationKey pos = key({0, 4}, {{-4, 5, 1}, {4, 1, 1}});
    pos.path = "lights.0.position";
    a.keys.push_back(pos);
    const std::vector<Override> o = frame_overrides(a, 2, "x.json");
    ASSERT_EQ(o.size(), 2u);
    EXPECT_EQ(o[0].path, "materials.red.n");
    EXPECT_EQ(o[0].json, "5");
    EXPECT_EQ(o[0].origin, "x.json: animation.keys.materials.red.n at frame 2 =");
    EXPECT_EQ(o[1].path, "lights.0.position");
    EXPECT_EQ(o[1].json, "[0, 3, 1]");
}

// --- through the loader ----------------------------------------------------------------------

TEST(Animation, FramesHaveTheInterpolatedValues) {
    const std::string json = scene_with(R"({"frames": 12, "fps": 30, "keys": {
        "materials.red.n": [[2, 10], [6, 50]],
        "lights.0.position": [[0, [-4, 5, 5]], [8, [4, 1, 5]]]}})");
    const SceneDesc first = parse(json);
    EXPECT_EQ(first.frame, 0);
    EXPECT_EQ(first.animation.frames, 12);
    EXPECT_EQ(first.animation.fps, 30);
    ASSERT_EQ(first.animation.keys.size(), 2u);
    EXPECT_FLOAT_EQ(material(first, "red").n, 10);
    expect_vec(first.lights[0].position, {-4, 5, 5});

    const float n_at[] = {10, 10, 10, 20, 30, 40, 50, 50, 50, 50, 50, 50};
    for (int f = 0; f < 12; ++f) {
        SCOPED_TRACE("frame " + std::to_string(f));
        const SceneDesc s = frame_of(json, f);
        EXPECT_EQ(s.frame, f);
        EXPECT_EQ(s.animation.frames, 12);
        EXPECT_FLOAT_EQ(material(s, "red").n, n_at[f]);
        const float t = std::min(f, 8) / 8.0f;
        expect_vec(s.lights[0].position, {-4 + 8 * t, 5 - 4 * t, 5});
    }
}

TEST(Animation, KeyframeValuesAreExactAtKeyframes) {
    const std::string json = scene_with(R"({"frames": 9, "keys": {
        "materials.red.n": [[0, 0.1], [4, 0.7], [8, 33.3]],
        "lights.0.intensity": [[0, [0.1, 0.2, 0.3]], [4, [0.7, 0.11, 0.13]]]}})");
    EXPECT_EQ(material(frame_of(json, 0), "red").n, 0.1f);
    EXPECT_EQ(material(frame_of(json, 4), "red").n, 0.7f);
    EXPECT_EQ(material(frame_of(json, 8), "red").n, 33.3f);
    const Rgb i = frame_of(json, 4).lights[0].intensity;
    EXPECT_EQ(i.x, 0.7f);
    EXPECT_EQ(i.y, 0.11f);
    EXPECT_EQ(i.z, 0.13f);
}

TEST(Animation, HeldBeforeTheFirstAndAfterTheLastKeyframe) {
    // The keys start after frame 0, and the last lies past the last frame (allowed).
    const std::string json =
        scene_with(R"({"frames": 10, "keys": {"objects.0.radius": [[3, 1], [5, 2], [12, 9]]}})");
    for (int f : {0, 1, 2, 3}) EXPECT_FLOAT_EQ(frame_of(json, f).objects[0].radius, 1) << f;
    EXPECT_FLOAT_EQ(frame_of(json, 4).objects[0].radius, 1.5f);
    EXPECT_FLOAT_EQ(frame_of(json, 9).objects[0].radius, 6);  // 2 + 7·4/7

    const std::string held =
        scene_with(R"({"frames": 10, "keys": {"objects.0.radius": [[2, 3]]}})");
    for (int f : {0, 2, 9}) EXPECT_FLOAT_EQ(frame_of(held, f).objects[0].radius, 3) << f;
}

TEST(Animation, ArrayValuesSetVectorsAndColours) {
    const std::string json = scene_with(R"({"frames": 5, "keys": {
        "objects.0.center": [[0, [0, 0, 0]], [4, [2, -4, 8]]],
        "materials.red.kd": [[0, [0, 0, 0]], [4, [1, 0.5, 0.25]]]}})");
    const SceneDesc s = frame_of(json, 2);
    expect_vec(s.objects[0].center, {1, -2, 4});
    expect_vec(material(s, "red").kd, {0.5f, 0.25f, 0.125f});
}

TEST(Animation, FramesOfASceneWithoutAnimation) {
    const std::string json = R"({"objects": [{"type": "sphere"}]})";
    const SceneDesc s = parse(json);
    EXPECT_EQ(s.animation.frames, 0);
    EXPECT_EQ(frame_of(json, 0).frame, 0);
    try {
        frame_of(json, 1);
        FAIL() << "a scene without animation has only frame 0";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()), "scenes/a.json: no frame 1 (frames 0 to 0)");
    }
    try {
        frame_of(scene_with(R"({"frames": 4})"), 4);
        FAIL() << "frame 4 of 4";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()), "scenes/a.json: no frame 4 (frames 0 to 3)");
    }
    EXPECT_THROW(frame_of(scene_with(R"({"frames": 4})"), -1), InputError);
}

// --- the orbit -------------------------------------------------------------------------------

std::string orbit_scene(const std::string& camera, const std::string& animation) {
    return R"({"camera": )" + camera + R"(, "objects": [{"type": "sphere"}], "animation": )" +
           animation + "}";
}

TEST(Animation, OrbitTurnsThePositionCounterClockwiseSeenFromUp) {
    const std::string json =
        orbit_scene(R"({"projection": "perspective", "position": [6, 3, 3], "look_at": [1, 2, 3]})",
                    R"({"frames": 4, "orbit": 360})");
    const Vec3 look_at(1, 2, 3);
    // Frame 0 unchanged.
    expect_vec(parse(json).camera.position, {6, 3, 3});
    expect_vec(frame_of(json, 0).camera.position, {6, 3, 3});
    // Frame 1: 90° about +y. Seen from above (+y), x points right and z down the page, so
    // counter-clockwise takes +x to −z: p − look_at = (5, 1, 0) → (0, 1, −5).
    const SceneDesc s1 = frame_of(json, 1);
    expect_vec(s1.camera.position, {1, 3, -2});
    expect_vec(s1.camera.look_at, look_at);
    expect_vec(s1.camera.up, {0, 1, 0});
    expect_vec(frame_of(json, 2).camera.position, {-4, 3, 3});
    expect_vec(frame_of(json, 3).camera.position, {1, 3, 8});
    for (int f = 0; f < 4; ++f) {
        EXPECT_NEAR(length(frame_of(json, f).camera.position - look_at), std::sqrt(26.0f), 1e-5f)
            << "the distance to look_at is kept, frame " << f;
    }
}

TEST(Animation, OrbitIsAboutUpWhateverItsLength) {
    // up = +z (length 3): counter-clockwise seen from +z takes +x to +y.
    const std::string json = orbit_scene(
        R"({"projection": "perspective", "position": [2, 0, 1], "look_at": [0, 0, 0],
            "up": [0, 0, 3]})",
        R"({"frames": 8, "orbit": 180})");
    expect_vec(frame_of(json, 4).camera.position, {0, 2, 1});
    const float h = std::sqrt(2.0f);
    expect_vec(frame_of(json, 2).camera.position, {h, h, 1});
    // A negative orbit turns the other way.
    const std::string back = orbit_scene(
        R"({"projection": "perspective", "position": [2, 0, 1], "look_at": [0, 0, 0],
            "up": [0, 0, 1]})",
        R"({"frames": 8, "orbit": -180})");
    expect_vec(frame_of(back, 4).camera.position, {0, -2, 1});
}

TEST(Animation, OrbitTurnsTheKeyedPosition) {
    // docs/SCENES.md#scene-files: the orbit comes after the keys.
    const std::string json = orbit_scene(
        R"({"projection": "perspective", "look_at": [0, 0, 0]})",
        R"({"frames": 4, "orbit": 360, "keys": {"camera.position": [[0, [2, 1, 0]], [2, [4, 1, 0]]]}})");
    expect_vec(frame_of(json, 0).camera.position, {2, 1, 0});
    expect_vec(frame_of(json, 1).camera.position, {0, 1, -3});  // (3, 1, 0) turned 90°
    expect_vec(frame_of(json, 2).camera.position, {-4, 1, 0});  // (4, 1, 0) turned 180°
    expect_vec(frame_of(json, 3).camera.position, {0, 1, 4});   // (4, 1, 0) turned 270°
}

TEST(Animation, ThingsPlacedByTheCameraFollowTheOrbit) {
    // With no lights, one light sits at the camera's upper left (docs/SCENES.md#scene-files): the
    // camera of frame f is the orbited one, so frame f is the scene with camera.position set to
    // where the orbit put it, the light included. So is a light without a position.
    for (const char* lights : {"", R"(, "lights": [{"intensity": 2}])"}) {
        SCOPED_TRACE(lights);
        const std::string json =
            std::string(R"({"camera": {"position": [0, 3, 10], "look_at": [0, 0.5, 0]},
                            "objects": [{"type": "sphere"}])") +
            lights + R"(, "animation": {"frames": 4, "orbit": 360}})";
        const SceneDesc s = frame_of(json, 1);
        expect_vec(s.camera.position, {10, 3, 0});
        const SceneDesc expected =
            parse(json, sets({"camera.position=[10,3,0]", "animation.orbit=0"}));
        ASSERT_EQ(s.lights.size(), 1u);
        expect_vec(s.lights[0].position, expected.lights[0].position, 1e-4f);
        expect_vec(s.lights[0].intensity, expected.lights[0].intensity, 1e-4f);
        // The light is not where frame 0's is.
        EXPECT_GT(length(s.lights[0].position - parse(json).lights[0].position), 1.0f);
    }
}

// --- keys and --set ----------------------------------------------------------------------------

TEST(Animation, OverridesWinOverTheKeys) {
    const std::string json = scene_with(R"({"frames": 5, "keys": {
        "materials.red.n": [[0, 10], [4, 50]],
        "lights.1.position": [[0, [0, 9, 0]], [4, [4, 9, 0]]]}})");
    // The command line overrides the scene, its animation included: --set on an animated path
    // holds it at every frame; the other keys still animate. An override may add to what a key
    // animates (lights.1) and change the animation.
    const std::vector<Override> o = sets({"materials.red.n=500", "materials.red.ks=0.25",
                                          "lights.1.intensity=3", "animation.frames=6"});
    const SceneDesc first = parse(json, o);
    EXPECT_EQ(first.animation.frames, 6);
    for (int f = 0; f < 6; ++f) {
        SCOPED_TRACE("frame " + std::to_string(f));
        const SceneDesc s = frame_of(json, f, o);
        EXPECT_FLOAT_EQ(material(s, "red").n, 500);
        expect_vec(material(s, "red").ks, Vec3(0.25f));
        ASSERT_EQ(s.lights.size(), 2u);
        expect_vec(s.lights[1].position, {float(std::min(f, 4)), 9, 0});
        expect_vec(s.lights[1].intensity, Vec3(3));
    }
    // A --set replacing the keys animates something else.
    const SceneDesc s =
        frame_of(json, 2, sets({"animation.keys={\"objects.0.radius\": [[0, 1], [4, 3]]}"}));
    EXPECT_FLOAT_EQ(s.objects[0].radius, 2);
    EXPECT_FLOAT_EQ(material(s, "red").n, 10);
}

TEST(Animation, OptionOverridesWinOverTheKeysToo) {
    // --width is an override named after its option: a quick preview of an animation that
    // keys image.width is at that width.
    const std::string json =
        scene_with(R"({"frames": 3, "keys": {"image.width": [[0, 32], [2, 64]]}})");
    const std::vector<Override> o = {Override{"image.width", "100", "--width"}};
    for (int f = 0; f < 3; ++f) EXPECT_EQ(frame_of(json, f, o).image.width, 100);
    EXPECT_EQ(frame_of(json, 1, {}).image.width, 48);
}

// --- meshes ------------------------------------------------------------------------------------

TEST(Animation, MeshesAreReadOnceForEveryFrame) {
    const auto dir = std::filesystem::temp_directory_path() /
                     ("luz_animation_test_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "tri.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    const std::string json = R"({"objects": [
        {"type": "mesh", "file": "tri.obj", "material": "gesso",
         "transform": {"translate": [0, 0, 0]}},
        {"type": "mesh", "file": "tri.obj", "material": "gesso"}],
      "animation": {"frames": 6, "keys": {"objects.0.transform.translate":
                                          [[0, [0, 0, 0]], [5, [5, 0, 0]]]}}})";
    MeshCache cache;
    const SceneDesc first = parse(json, {}, &cache, dir.string());
    ASSERT_EQ(cache.size(), 1u);  // one file, read once over six frames and two objects
    const std::shared_ptr<const MeshData> mesh = cache.begin()->second;
    EXPECT_EQ(first.objects[0].mesh, mesh);
    EXPECT_EQ(first.objects[1].mesh, mesh);

    // Later frames take it from the cache: the file is not read again.
    std::filesystem::remove(dir / "tri.obj");
    for (int f : {1, 3, 5}) {
        const SceneDesc s = frame_of(json, f, {}, &cache, dir.string());
        EXPECT_EQ(s.objects[0].mesh, mesh) << f;
        EXPECT_EQ(s.objects[1].mesh, mesh) << f;
        expect_vec(s.objects[0].transform.point({0, 0, 0}), {float(f), 0, 0});
    }
    EXPECT_EQ(cache.size(), 1u);
    // Without the cache, the missing file is noticed.
    EXPECT_THROW(frame_of(json, 1, {}, nullptr, dir.string()), InputError);
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace luz
