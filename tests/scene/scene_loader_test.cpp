// Tests of the scene loader (docs/SCENES.md#scene-files): defaults, every key, materials,
// transforms, --set overrides, the implicit light, scene files and demo scenes by name.
#include "scene/scene_loader.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "scene_loader_fixtures.h"

namespace luz {
namespace {

using test::expect_vec;
using test::parse;
using test::sets;
using ::testing::HasSubstr;

TEST(SceneLoader, DefaultsOfTheSmallestScene) {
    const SceneDesc s = parse(R"({"objects":[{"type":"sphere"}]})");
    EXPECT_EQ(s.name, "a");
    EXPECT_EQ(s.source, "scenes/a.json");

    EXPECT_EQ(s.image.width, 800);
    EXPECT_EQ(s.image.height, 600);
    expect_vec(s.image.background, {0.05f, 0.05f, 0.08f});
    EXPECT_EQ(s.image.encoding, Encoding::linear);

    EXPECT_EQ(s.camera.projection, Projection::orthographic);
    expect_vec(s.camera.position, {0, 3, 10});
    expect_vec(s.camera.look_at, {0, 0.5f, 0});
    expect_vec(s.camera.up, {0, 1, 0});
    EXPECT_FLOAT_EQ(s.camera.view_height, 6.0f);
    EXPECT_FLOAT_EQ(s.camera.fov_y, 40.0f);

    EXPECT_EQ(s.render.pipeline, Pipeline::zbuffer);
    EXPECT_EQ(s.render.model, Model::phong);
    EXPECT_EQ(s.render.max_depth, 5);
    EXPECT_FALSE(s.render.tree_attenuation);
    EXPECT_EQ(s.geometry.tessellation, 64);
    EXPECT_EQ(s.geometry.accel, Accel::bvh);
    EXPECT_EQ(s.render.antialias.mode, AaMode::none);
    EXPECT_EQ(s.render.antialias.samples, 4);
    EXPECT_EQ(s.render.antialias.filter, AaFilter::box);
    EXPECT_FALSE(s.render.antialias.jitter);
    EXPECT_FLOAT_EQ(s.render.antialias.threshold, 0.1f);
    EXPECT_EQ(s.render.antialias.max_level, 3);

    expect_vec(s.ambient, Vec3(1.0f));
    EXPECT_FLOAT_EQ(s.attenuation_k, 1.0f);

    // The implicit light: position + (−u + v)·(0.5·|position − look_at|) with u = (1,0,0),
    // v = (0, 10, −2.5)/|(0, 2.5, 10)|: (−5.154, 8, 8.75); under phong Il = d + K.
    ASSERT_EQ(s.lights.size(), 1u);
    const float half = 0.5f * std::sqrt(2.5f * 2.5f + 10.0f * 10.0f);
    expect_vec(s.lights[0].position, {-half, 8.0f, 8.75f}, 1e-4f);
    const float d = std::sqrt(half * half + 7.5f * 7.5f + 8.75f * 8.75f);
    expect_vec(s.lights[0].intensity, Vec3(d + 1.0f), 1e-4f);
    EXPECT_FLOAT_EQ(s.lights[0].radius, 0.0f);

    ASSERT_EQ(s.materials.size(), 1u);
    const Material& m = s.materials[0];
    EXPECT_EQ(m.name, "default");
    expect_vec(m.ka, Vec3(0.1f));
    expect_vec(m.kd, Vec3(0.45f));
    expect_vec(m.ks, Vec3(0.3f));
    EXPECT_FLOAT_EQ(m.n, 20.0f);
    EXPECT_FLOAT_EQ(m.reflection, 0.0f);
    EXPECT_FLOAT_EQ(m.transparency, 0.0f);
    EXPECT_FLOAT_EQ(m.ior, 1.0f);
    EXPECT_FALSE(m.checker.has_value());

    ASSERT_EQ(s.objects.size(), 1u);
    const ObjectDesc& o = s.objects[0];
    EXPECT_EQ(o.type, ShapeType::sphere);
    EXPECT_EQ(o.material, 0);
    EXPECT_EQ(o.path, "objects.0");
    expect_vec(o.center, {0, 0, 0});
    EXPECT_FLOAT_EQ(o.radius, 1.0f);
    expect_vec(o.transform.point({1, 2, 3}), {1, 2, 3});
    expect_vec(o.transform.vector({1, 2, 3}), {1, 2, 3});
}

TEST(SceneLoader, EveryKeyIsReadIntoItsField) {
    const SceneDesc s = parse(R"({
      "image":  { "width": 320, "height": 200, "background": [0.1, 0.2, 0.3], "encoding": "srgb" },
      "camera": { "projection": "perspective", "position": [1, 2, 3], "look_at": [0, 1, -1],
                  "up": [0, 0.5, 0], "view_height": 4.5, "fov_y": 55 },
      "render": { "pipeline": "raytrace", "model": "lambert", "max_depth": 7,
                  "tree_attenuation": true, "tessellation": 12, "accel": "none",
                  "antialias": { "mode": "adaptive", "samples": 9, "filter": "tent",
                                 "jitter": true, "threshold": 0.25, "max_level": 2 } },
      "ambient": [0.2, 0.3, 0.4],
      "attenuation_k": 2.5,
      "lights": [ { "position": [5, 8, 6], "intensity": [1, 0.5, 0.25], "radius": 0.3 },
                  { "position": [-1, 2, -3] } ],
      "materials": {
        "red": { "ka": [0.1, 0.02, 0.03], "kd": [0.8, 0.1, 0.2], "ks": [0.5, 0.6, 0.7], "n": 30,
                 "reflection": 0.25, "transparency": 0.5, "ior": 1.7 }
      },
      "objects": [
        { "type": "sphere",   "center": [0, 1, 0], "radius": 1.5, "material": "red" },
        { "type": "box",      "min": [-3, 0, -1], "max": [-2, 1, 0] },
        { "type": "cylinder", "base": [2, 0, 0], "axis": [0, 2, 0], "radius": 0.5, "height": 1.5, "caps": false },
        { "type": "cone",     "base": [4, 0, 0], "axis": [1, 0, 0], "radius": 0.6, "height": 1.25, "cap": false },
        { "type": "torus",    "center": [0, 0.3, 3], "axis": [0, 0, 1], "major_radius": 1, "minor_radius": 0.3 },
        { "type": "plane",    "point": [0, -1, 0], "normal": [0, 0, 2] },
        { "type": "triangle", "vertices": [[0,0,0], [2,0,0], [0,3,1]] }
      ]
    })");
    EXPECT_EQ(s.image.width, 320);
    EXPECT_EQ(s.image.height, 200);
    expect_vec(s.image.background, {0.1f, 0.2f, 0.3f});
    EXPECT_EQ(s.image.encoding, Encoding::srgb);

    EXPECT_EQ(s.camera.projection, Projection::perspective);
    expect_vec(s.camera.position, {1, 2, 3});
    expect_vec(s.camera.look_at, {0, 1, -1});
    expect_vec(s.camera.up, {0, 0.5f, 0});
    EXPECT_FLOAT_EQ(s.camera.view_height, 4.5f);
    EXPECT_FLOAT_EQ(s.camera.fov_y, 55.0f);

    EXPECT_EQ(s.render.pipeline, Pipeline::raytrace);
    EXPECT_EQ(s.render.model, Model::lambert);
    EXPECT_EQ(s.render.max_depth, 7);
    EXPECT_TRUE(s.render.tree_attenuation);
    EXPECT_EQ(s.geometry.tessellation, 12);
    EXPECT_EQ(s.geometry.accel, Accel::none);
    EXPECT_EQ(s.render.antialias.mode, AaMode::adaptive);
    EXPECT_EQ(s.render.antialias.samples, 9);
    EXPECT_EQ(s.render.antialias.filter, AaFilter::tent);
    EXPECT_TRUE(s.render.antialias.jitter);
    EXPECT_FLOAT_EQ(s.render.antialias.threshold, 0.25f);
    EXPECT_EQ(s.render.antialias.max_level, 2);

    expect_vec(s.ambient, {0.2f, 0.3f, 0.4f});
    EXPECT_FLOAT_EQ(s.attenuation_k, 2.5f);

    ASSERT_EQ(s.lights.size(), 2u);
    expect_vec(s.lights[0].position, {5, 8, 6});
    expect_vec(s.lights[0].intensity, {1, 0.5f, 0.25f});
    EXPECT_FLOAT_EQ(s.lights[0].radius, 0.3f);
    expect_vec(s.lights[1].position, {-1, 2, -3});
    expect_vec(s.lights[1].intensity, Vec3(1.0f));  // a light without intensity: Il = 1
    EXPECT_FLOAT_EQ(s.lights[1].radius, 0.0f);

    ASSERT_EQ(s.materials.size(), 2u);
    const Material& red = s.materials[1];
    EXPECT_EQ(red.name, "red");
    expect_vec(red.ka, {0.1f, 0.02f, 0.03f});
    expect_vec(red.kd, {0.8f, 0.1f, 0.2f});
    expect_vec(red.ks, {0.5f, 0.6f, 0.7f});
    EXPECT_FLOAT_EQ(red.n, 30.0f);
    EXPECT_FLOAT_EQ(red.reflection, 0.25f);
    EXPECT_FLOAT_EQ(red.transparency, 0.5f);
    EXPECT_FLOAT_EQ(red.ior, 1.7f);

    ASSERT_EQ(s.objects.size(), 7u);
    const auto& o = s.objects;
    EXPECT_EQ(o[0].type, ShapeType::sphere);
    expect_vec(o[0].center, {0, 1, 0});
    EXPECT_FLOAT_EQ(o[0].radius, 1.5f);
    EXPECT_EQ(o[0].material, 1);
    EXPECT_EQ(o[1].type, ShapeType::box);
    expect_vec(o[1].min, {-3, 0, -1});
    expect_vec(o[1].max, {-2, 1, 0});
    EXPECT_EQ(o[1].material, 0);
    EXPECT_EQ(o[2].type, ShapeType::cylinder);
    expect_vec(o[2].base, {2, 0, 0});
    expect_vec(o[2].axis, {0, 2, 0});
    EXPECT_FLOAT_EQ(o[2].radius, 0.5f);
    EXPECT_FLOAT_EQ(o[2].height, 1.5f);
    EXPECT_FALSE(o[2].caps);
    EXPECT_EQ(o[3].type, ShapeType::cone);
    expect_vec(o[3].base, {4, 0, 0});
    expect_vec(o[3].axis, {1, 0, 0});
    EXPECT_FLOAT_EQ(o[3].radius, 0.6f);
    EXPECT_FLOAT_EQ(o[3].height, 1.25f);
    EXPECT_FALSE(o[3].caps);
    EXPECT_EQ(o[4].type, ShapeType::torus);
    expect_vec(o[4].center, {0, 0.3f, 3});
    expect_vec(o[4].axis, {0, 0, 1});
    EXPECT_FLOAT_EQ(o[4].major_radius, 1.0f);
    EXPECT_FLOAT_EQ(o[4].minor_radius, 0.3f);
    EXPECT_EQ(o[5].type, ShapeType::plane);
    expect_vec(o[5].point, {0, -1, 0});
    expect_vec(o[5].normal, {0, 0, 2});
    EXPECT_EQ(o[6].type, ShapeType::triangle);
    expect_vec(o[6].vertices[0], {0, 0, 0});
    expect_vec(o[6].vertices[1], {2, 0, 0});
    expect_vec(o[6].vertices[2], {0, 3, 1});
    for (std::size_t i = 0; i < o.size(); ++i) EXPECT_EQ(o[i].path, "objects." + std::to_string(i));
}

TEST(SceneLoader, ScalarsStandForAllThreeChannels) {
    const SceneDesc s = parse(R"({
      "image": { "background": 0.3 }, "ambient": 0.5,
      "lights": [ { "position": [0, 5, 0], "intensity": 2 } ],
      "materials": { "m": { "ka": 0.2, "kd": 0.6, "ks": 0.7,
                            "checker": { "ka": 0.01, "kd": 0.2 } } },
      "objects": [ { "type": "sphere", "material": "m" } ] })");
    expect_vec(s.image.background, Vec3(0.3f));
    expect_vec(s.ambient, Vec3(0.5f));
    expect_vec(s.lights[0].intensity, Vec3(2.0f));
    const Material& m = s.materials[1];
    expect_vec(m.ka, Vec3(0.2f));
    expect_vec(m.kd, Vec3(0.6f));
    expect_vec(m.ks, Vec3(0.7f));
    expect_vec(m.checker->ka, Vec3(0.01f));
    expect_vec(m.checker->kd, Vec3(0.2f));
}

TEST(SceneLoader, TransformIsTranslateRotateZYXScale) {
    // p = (1,1,1); S = (1,2,3) → (1,2,3); Rx(90°) → (1,−3,2); Ry(90°) → (2,−3,−1);
    // Rz(90°) → (3,2,−1); T = (10,20,30) → (13,22,29).
    const SceneDesc s = parse(R"({"objects":[{"type":"sphere",
        "transform": {"scale": [1, 2, 3], "rotate": [90, 90, 90], "translate": [10, 20, 30]}}]})");
    const Affine& t = s.objects[0].transform;
    expect_vec(t.point({1, 1, 1}), {13, 22, 29}, 1e-4f);
    expect_vec(t.vector({1, 1, 1}), {3, 2, -1}, 1e-4f);

    // Right-hand rule about y: x goes to −z. A scalar scale scales all axes.
    const SceneDesc r = parse(R"({"objects":[{"type":"sphere",
        "transform": {"scale": 2, "rotate": [0, 90, 0]}}]})");
    expect_vec(r.objects[0].transform.point({1, 0, 0}), {0, 0, -2}, 1e-5f);
    // A negative scale mirrors.
    const SceneDesc m =
        parse(R"({"objects":[{"type":"sphere", "transform": {"scale": [-1, 1, 1]}}]})");
    expect_vec(m.objects[0].transform.point({1, 2, 3}), {-1, 2, 3});
}

TEST(SceneLoader, MaterialFromPresetWithOverrides) {
    const SceneDesc s = parse(R"({
      "materials": { "mirror": { "preset": "metal_polido", "reflection": 0.8 },
                     "glass": { "preset": "glass", "ior": 1.6 } },
      "objects": [ { "type": "sphere", "material": "mirror" },
                   { "type": "sphere", "material": "glass" } ] })");
    ASSERT_EQ(s.materials.size(), 3u);
    const Material& mirror = s.materials[s.objects[0].material];
    EXPECT_EQ(mirror.name, "mirror");
    EXPECT_FLOAT_EQ(mirror.reflection, 0.8f);  // overridden
    expect_vec(mirror.ks, Vec3(0.9f));         // from the preset
    EXPECT_FLOAT_EQ(mirror.n, 200.0f);
    const Material& glass = s.materials[s.objects[1].material];
    EXPECT_EQ(glass.name, "glass");
    EXPECT_FLOAT_EQ(glass.ior, 1.6f);
    EXPECT_FLOAT_EQ(glass.transparency, 0.9f);
}

TEST(SceneLoader, ReflectanceIsConstantUnlessSchlick) {
    // docs/SCENES.md#reflectance: `reflectance` per material, `constant` by default; the metal
    // presets bring `schlick`, which a material may override like any constant.
    const SceneDesc s = parse(R"({
      "materials": { "plain": { "ks": 0.5 },
                     "fresnel_like": { "ks": 0.04, "reflectance": "schlick" },
                     "flat_gold": { "preset": "ouro", "reflectance": "constant" },
                     "gold": { "preset": "gold" } },
      "objects": [ { "type": "sphere", "material": "plain" },
                   { "type": "sphere", "material": "fresnel_like" },
                   { "type": "sphere", "material": "flat_gold" },
                   { "type": "sphere", "material": "gold" },
                   { "type": "sphere", "material": "cobre" },
                   { "type": "sphere", "material": "glass" } ] })");
    const auto curve = [&](int object) {
        return s.materials[s.objects[object].material].reflectance;
    };
    EXPECT_EQ(s.materials[0].reflectance, Reflectance::constant);  // the default material
    EXPECT_EQ(curve(0), Reflectance::constant);
    EXPECT_EQ(curve(1), Reflectance::schlick);
    EXPECT_EQ(curve(2), Reflectance::constant);
    expect_vec(s.materials[s.objects[2].material].ks, {1.0f, 0.71f, 0.29f});  // the rest stays
    EXPECT_EQ(curve(3), Reflectance::schlick);
    EXPECT_EQ(curve(4), Reflectance::schlick);
    EXPECT_EQ(curve(5), Reflectance::constant);
}

TEST(SceneLoader, SetChangesTheReflectance) {
    const char* scene = R"({"materials": {"red": {"kd": [0.8, 0.1, 0.1]}},
                            "objects": [{"type": "sphere", "material": "red"}]})";
    EXPECT_EQ(parse(scene).materials[1].reflectance, Reflectance::constant);
    for (const char* set :
         {"materials.red.reflectance=\"schlick\"", "materials.red.reflectance=schlick"}) {
        EXPECT_EQ(parse(scene, sets({set})).materials[1].reflectance, Reflectance::schlick) << set;
    }
}

TEST(SceneLoader, CheckerIsParsed) {
    const SceneDesc s = parse(R"({
      "materials": { "floor": { "kd": 0.8, "checker": { "size": 0.5, "ka": [0.01, 0.02, 0.03],
                                                        "kd": [0.1, 0.2, 0.3] } },
                     "plain": { "checker": { "size": 2 } } },
      "objects": [ { "type": "plane", "material": "floor" } ] })");
    const Material& floor = s.materials[1];
    ASSERT_TRUE(floor.checker.has_value());
    EXPECT_FLOAT_EQ(floor.checker->size, 0.5f);
    expect_vec(floor.checker->ka, {0.01f, 0.02f, 0.03f});
    expect_vec(floor.checker->kd, {0.1f, 0.2f, 0.3f});
    const Material& plain = s.materials[2];
    ASSERT_TRUE(plain.checker.has_value());
    EXPECT_FLOAT_EQ(plain.checker->size, 2.0f);
    expect_vec(plain.checker->kd, Vec3(0.1f));  // Checker's default
}

TEST(SceneLoader, MaterialReferencesShareOneEntryPerName) {
    const SceneDesc s = parse(R"({
      "materials": { "red": { "kd": [0.8, 0.1, 0.1] } },
      "objects": [ { "type": "sphere", "material": "vidro" },
                   { "type": "sphere", "material": "glass" },
                   { "type": "sphere", "material": "red" },
                   { "type": "sphere", "material": "red" },
                   { "type": "sphere", "material": { "preset": "madeira", "n": 7 } },
                   { "type": "sphere", "material": "wood" },
                   { "type": "sphere" } ] })");
    // default, red, vidro, inline, madeira
    ASSERT_EQ(s.materials.size(), 5u);
    EXPECT_EQ(s.objects[0].material, s.objects[1].material);
    EXPECT_EQ(s.materials[s.objects[0].material].name, "vidro");
    EXPECT_FLOAT_EQ(s.materials[s.objects[0].material].ior, 1.5f);
    EXPECT_EQ(s.objects[2].material, 1);
    EXPECT_EQ(s.objects[3].material, 1);
    const Material& inline_m = s.materials[s.objects[4].material];
    EXPECT_EQ(inline_m.name, "objects.4.material");
    EXPECT_FLOAT_EQ(inline_m.n, 7.0f);
    EXPECT_EQ(s.materials[s.objects[5].material].name, "madeira");
    EXPECT_FLOAT_EQ(s.materials[s.objects[5].material].n, 10.0f);
    EXPECT_EQ(s.objects[6].material, 0);
}

TEST(SceneLoader, MaterialNamedDefaultReplacesTheDefault) {
    const SceneDesc s = parse(R"({"materials": {"default": {"kd": 0.7}},
                                  "objects": [{"type": "sphere"}]})");
    ASSERT_EQ(s.materials.size(), 1u);
    expect_vec(s.materials[0].kd, Vec3(0.7f));
    EXPECT_EQ(s.objects[0].material, 0);
}

TEST(SceneLoader, SetOverridesNumbersArraysAndBareWords) {
    const SceneDesc s = parse(
        R"({"materials": {"red": {"kd": [0.8, 0.1, 0.1], "n": 30}},
            "lights": [{"position": [1, 2, 3]}],
            "objects": [{"type": "sphere", "radius": 1, "material": "red"}]})",
        sets({"objects.0.radius=2", "lights.0.intensity=[1,0.9,0.8]", "render.pipeline=raytrace",
              "materials.red.n=4", "camera.projection=\"perspective\"", "image.width=1024"}));
    EXPECT_FLOAT_EQ(s.objects[0].radius, 2.0f);
    expect_vec(s.lights[0].intensity, {1, 0.9f, 0.8f});
    EXPECT_EQ(s.render.pipeline, Pipeline::raytrace);
    EXPECT_FLOAT_EQ(s.materials[1].n, 4.0f);
    expect_vec(s.materials[1].kd, {0.8f, 0.1f, 0.1f});  // untouched neighbours
    EXPECT_EQ(s.camera.projection, Projection::perspective);
    EXPECT_EQ(s.image.width, 1024);
}

TEST(SceneLoader, SetAppendsAndCreatesMissingKeys) {
    const SceneDesc s =
        parse(R"({"objects": [{"type": "sphere"}]})",
              sets({"objects.1={\"type\":\"box\"}", "objects.2.type=cone", "objects.2.height=3",
                    "lights.0.position=[1,2,3]", "materials.blue.kd=[0.1,0.2,0.9]",
                    "objects.0.material=blue", "render.antialias.mode=grid"}));
    ASSERT_EQ(s.objects.size(), 3u);
    EXPECT_EQ(s.objects[1].type, ShapeType::box);
    EXPECT_EQ(s.objects[2].type, ShapeType::cone);
    EXPECT_FLOAT_EQ(s.objects[2].height, 3.0f);
    ASSERT_EQ(s.lights.size(), 1u);
    expect_vec(s.lights[0].position, {1, 2, 3});
    EXPECT_EQ(s.materials[s.objects[0].material].name, "blue");
    expect_vec(s.materials[s.objects[0].material].kd, {0.1f, 0.2f, 0.9f});
    EXPECT_EQ(s.render.antialias.mode, AaMode::grid);
}

TEST(SceneLoader, LaterOverridesWin) {
    const SceneDesc s = parse(R"({"objects": [{"type": "sphere"}]})",
                              sets({"objects.0.radius=2", "objects.0.radius=3"}));
    EXPECT_FLOAT_EQ(s.objects[0].radius, 3.0f);
}

TEST(SceneLoader, ParseSetSplitsAtTheFirstEquals) {
    const Override o = parse_set("materials.red.kd=[0.5,0.5,0.5]");
    EXPECT_EQ(o.path, "materials.red.kd");
    EXPECT_EQ(o.json, "[0.5,0.5,0.5]");
    EXPECT_EQ(o.origin, "--set");
}

TEST(SceneLoader, ImplicitLightUnderLambertHasUnitIntensity) {
    const SceneDesc s =
        parse(R"({"render": {"model": "lambert"}, "lights": [], "objects": [{"type": "sphere"}]})");
    ASSERT_EQ(s.lights.size(), 1u);
    expect_vec(s.lights[0].intensity, Vec3(1.0f));
    // Upper left of the camera: left of it (−u = −x) and above it.
    EXPECT_LT(s.lights[0].position.x, 0.0f);
    EXPECT_GT(s.lights[0].position.y, s.camera.position.y);
}

TEST(SceneLoader, ImplicitLightFollowsTheCameraAndK) {
    const SceneDesc s = parse(R"({"camera": {"position": [0, 0, 8], "look_at": [0, 0, 0]},
                                  "attenuation_k": 3, "objects": []})");
    ASSERT_EQ(s.lights.size(), 1u);
    // u = (1,0,0), v = (0,1,0), 0.5·d = 4: (−4, 4, 8); its distance to look_at is √96.
    expect_vec(s.lights[0].position, {-4, 4, 8}, 1e-5f);
    expect_vec(s.lights[0].intensity, Vec3(std::sqrt(96.0f) + 3.0f), 1e-4f);
}

TEST(SceneLoader, ExplicitLightsReplaceTheImplicitOne) {
    const SceneDesc s = parse(R"({"lights": [{"position": [1, 1, 1], "intensity": 0.5}]})");
    ASSERT_EQ(s.lights.size(), 1u);
    expect_vec(s.lights[0].position, {1, 1, 1});
    expect_vec(s.lights[0].intensity, Vec3(0.5f));
}

TEST(SceneLoader, LoadsAFileNamedByItsStem) {
    const auto dir = std::filesystem::temp_directory_path() / "luz_scene_test";
    std::filesystem::create_directories(dir);
    const auto file = dir / "my_scene.json";
    std::ofstream(file) << R"({"objects": [{"type": "box"}]})";
    const SceneDesc s = load_scene(file.string(), sets({"objects.0.max=[1,1,1]"}));
    EXPECT_EQ(s.name, "my_scene");
    EXPECT_EQ(s.source, file.string());
    expect_vec(s.objects[0].max, {1, 1, 1});

    // A mesh: the OBJ file is resolved next to the scene, and loaded.
    std::ofstream(file) << R"({"objects": [{"type": "mesh", "file": "tri.obj", "smooth": false}]})";
    try {
        load_scene(file.string());
        FAIL() << "a missing OBJ file must be refused";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()), file.string() + ": objects.0.file: cannot read " +
                                             (dir / "tri.obj").string() +
                                             ": No such file or directory");
    }
    std::ofstream(dir / "tri.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    const SceneDesc m = load_scene(file.string());
    ASSERT_NE(m.objects[0].mesh, nullptr);
    EXPECT_EQ(m.objects[0].mesh->triangle_count(), 1u);
    EXPECT_FALSE(m.objects[0].smooth);
    std::filesystem::remove_all(dir);
}

TEST(SceneLoader, MissingFileIsAnInputError) {
    try {
        load_scene("/nonexistent/dir/scene.json");
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_THAT(e.what(), HasSubstr("/nonexistent/dir/scene.json: cannot read"));
    }
    EXPECT_THROW(load_scene(std::filesystem::temp_directory_path().string()), InputError);
    EXPECT_THROW(load_scene("demo:no_such_demo"), InputError);
}

TEST(SceneLoader, DemoScenesLoadByName) {
    const SceneDesc s = load_scene("demo:primitives", sets({"image.width=64"}));
    EXPECT_EQ(s.name, "primitives");
    EXPECT_EQ(s.source, "demo:primitives");
    EXPECT_EQ(s.image.width, 64);
    try {
        load_scene("demo:primitives", sets({"objects.1.radius=-1"}));
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()), "--set objects.1.radius=-1: must be > 0, got -1");
    }
}

}  // namespace
}  // namespace luz
