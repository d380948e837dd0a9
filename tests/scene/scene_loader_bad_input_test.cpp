// The messages of bad scenes (docs/SCENES.md#scene-files): each bad scene or --set argument is
// refused with one line naming the file or option and the place in it.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <ostream>
#include <string>
#include <vector>

#include "scene/scene_loader.h"
#include "scene_loader_fixtures.h"

namespace luz {
namespace {

using test::parse;
using test::sets;
using ::testing::HasSubstr;

// A bad scene (or override) and a fragment its message must contain.
struct BadCase {
    const char* json;
    std::vector<const char*> overrides;
    const char* expected;
};

void PrintTo(const BadCase& c, std::ostream* os) { *os << c.json << " → " << c.expected; }

class BadScene : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadScene, IsRefusedWithAMessageNamingThePlace) {
    const BadCase& c = GetParam();
    try {
        std::vector<Override> overrides;
        for (const char* a : c.overrides) overrides.push_back(parse_set(a));
        parse(c.json, overrides);
        FAIL() << "accepted: " << c.json;
    } catch (const InputError& e) {
        const std::string msg = e.what();
        EXPECT_THAT(msg, HasSubstr(c.expected));
        EXPECT_EQ(msg.find('\n'), std::string::npos) << "one line: " << msg;
        if (c.overrides.empty()) {
            EXPECT_EQ(msg.rfind("scenes/a.json", 0), 0u) << msg;
        }
    }
}

const BadCase kBadCases[] = {
    // syntax: line:column
    {"{\"objects\": [\n  {\"type\": \"sphere\",}\n]}", {}, "scenes/a.json:2:21: JSON syntax error"},
    {"{\"a\": 1,\n \"b\": x}", {}, "scenes/a.json:2:7: JSON syntax error"},
    {"{\"objects\": [", {}, "scenes/a.json:1:14: JSON syntax error"},
    {"", {}, "scenes/a.json:1:1: JSON syntax error"},
    {"{\"ambient\":\n   1e999}", {}, "scenes/a.json:2:4: number out of range"},
    {"[1, 2]", {}, "scenes/a.json: expected a JSON object at the top level"},
    // unknown keys at every level
    {R"({"objects":[{"type":"sphere","colour":[1,0,0]}]})",
     {},
     "scenes/a.json: objects.0.colour: unknown key (known: type, center, radius, material, "
     "transform)"},
    {R"({"camra": {}})", {}, "scenes/a.json: camra: unknown key"},
    {R"({"camera": {"fov": 30}})", {}, "camera.fov: unknown key"},
    {R"({"render": {"antialias": {"sample": 4}}})", {}, "render.antialias.sample: unknown key"},
    {R"({"materials": {"red": {"kd": 0.5, "shininess": 3}}})",
     {},
     "materials.red.shininess: unknown key"},
    {R"({"materials": {"f": {"checker": {"size": 1, "colour": 0}}}})",
     {},
     "materials.f.checker.colour: unknown key"},
    {R"({"lights": [{"position": [0,1,0], "color": 1}]})", {}, "lights.0.color: unknown key"},
    {R"({"objects": [{"type": "sphere", "transform": {"rotation": [0,1,0]}}]})",
     {},
     "objects.0.transform.rotation: unknown key"},
    {R"({"objects": [{"type": "box", "radius": 1}]})", {}, "objects.0.radius: unknown key"},
    // wrong types and non-finite numbers
    {R"({"camera": {"position": [0, 1]}})",
     {},
     "scenes/a.json: camera.position: expected an array of 3 numbers"},
    {R"({"camera": {"position": "here"}})", {}, "camera.position: expected an array of 3 numbers"},
    {R"({"image": {"width": "800"}})", {}, "image.width: expected an integer"},
    {R"({"image": {"width": 800.5}})", {}, "image.width: expected an integer, got 800.5"},
    {R"({"render": {"tree_attenuation": 1}})",
     {},
     "render.tree_attenuation: expected true or false"},
    {R"({"objects": {"type": "sphere"}})", {}, "objects: expected an array"},
    {R"({"objects": [{"radius": 1}]})", {}, "objects.0: missing key \"type\""},
    {R"({"objects": [{"type": "sphere", "radius": 1e39}]})",
     {},
     "objects.0.radius: must be a finite number"},
    {R"({"lights": [{"position": [0, 1e39, 0]}]})", {}, "lights.0.position: must be a finite"},
    // ranges
    {R"({"objects":[{"type":"sphere"},{"type":"sphere"},{"type":"sphere","radius":-1}]})",
     {},
     "scenes/a.json: objects.2.radius: must be > 0, got -1"},
    {R"({"objects":[{"type":"cylinder","height":0}]})", {}, "objects.0.height: must be > 0, got 0"},
    {R"({"objects":[{"type":"cone","radius":0}]})", {}, "objects.0.radius: must be > 0"},
    {R"({"objects":[{"type":"sphere","radius":1e-50}]})",
     {},
     "objects.0.radius: must be > 0, got 1e-50"},
    {R"({"objects":[{"type":"torus","major_radius":0.5,"minor_radius":0.5}]})",
     {},
     "objects.0.minor_radius: must be < major_radius"},
    {R"({"objects":[{"type":"torus","minor_radius":-0.1}]})",
     {},
     "objects.0.minor_radius: must be > 0"},
    {R"({"objects":[{"type":"box","min":[0,0,0],"max":[1,0,1]}]})",
     {},
     "objects.0.max: must be greater than min on every axis"},
    {R"({"camera": {"view_height": 0}})", {}, "camera.view_height: must be > 0, got 0"},
    {R"({"materials": {"red": {"kd": [0.5, 1.5, 0.2]}}})",
     {},
     "scenes/a.json: materials.red.kd: must be in [0, 1], got 1.5"},
    {R"({"materials": {"red": {"ka": -0.1}}})",
     {},
     "materials.red.ka: must be in [0, 1], got -0.1"},
    {R"({"materials": {"red": {"ks": 2}}})", {}, "materials.red.ks: must be in [0, 1], got 2"},
    {R"({"materials": {"red": {"reflection": 1.2}}})",
     {},
     "materials.red.reflection: must be in [0, 1]"},
    {R"({"materials": {"red": {"transparency": -1}}})",
     {},
     "materials.red.transparency: must be in [0, 1]"},
    {R"({"materials": {"red": {"ior": 0.9}}})", {}, "materials.red.ior: must be >= 1, got 0.9"},
    {R"({"materials": {"red": {"n": 0}}})", {}, "materials.red.n: must be > 0, got 0"},
    {R"({"materials": {"f": {"checker": {"size": 0}}}})",
     {},
     "materials.f.checker.size: must be > 0"},
    {R"({"attenuation_k": 0})", {}, "attenuation_k: must be > 0, got 0"},
    {R"({"ambient": [1, -0.5, 1]})", {}, "ambient: must be >= 0, got -0.5"},
    {R"({"lights": [{"position": [0,1,0], "intensity": -1}]})",
     {},
     "lights.0.intensity: must be >= 0"},
    {R"({"lights": [{"position": [0,1,0], "radius": -1}]})", {}, "lights.0.radius: must be >= 0"},
    {R"({"objects":[{"type":"cylinder","axis":[0,0,0]}]})",
     {},
     "objects.0.axis: must not be zero-length"},
    {R"({"objects":[{"type":"plane","normal":[0,0,0]}]})",
     {},
     "objects.0.normal: must not be zero-length"},
    {R"({"camera": {"up": [0, 0, 0]}})", {}, "camera.up: must not be zero-length"},
    {R"({"camera": {"position": [0, 5, 0], "look_at": [0, 0, 0]}})",
     {},
     "camera.up: must not be parallel to the view direction"},
    {R"({"camera": {"position": [1, 2, 3], "look_at": [1, 2, 3]}})",
     {},
     "camera.look_at: must differ from camera.position"},
    {R"({"camera": {"fov_y": 180}})", {}, "camera.fov_y: must be in (0, 180), got 180"},
    {R"({"camera": {"fov_y": 0}})", {}, "camera.fov_y: must be in (0, 180)"},
    {R"({"image": {"width": 0}})", {}, "image.width: must be in [1, 65536], got 0"},
    {R"({"image": {"height": 70000}})", {}, "image.height: must be in [1, 65536]"},
    {R"({"image": {"width": 65536, "height": 65536}})", {}, "image: width*height must be at most"},
    {R"({"render": {"tessellation": 2}})", {}, "render.tessellation: must be in [3, 4096], got 2"},
    {R"({"render": {"max_depth": 65}})", {}, "render.max_depth: must be in [0, 64], got 65"},
    {R"({"render": {"antialias": {"samples": 5}}})",
     {},
     "render.antialias.samples: must be a perfect square in [1, 256]"},
    {R"({"render": {"antialias": {"samples": 289}}})",
     {},
     "render.antialias.samples: must be a perfect square"},
    {R"({"render": {"antialias": {"threshold": -0.1}}})",
     {},
     "render.antialias.threshold: must be >= 0"},
    {R"({"render": {"antialias": {"max_level": 7}}})",
     {},
     "render.antialias.max_level: must be in [0, 6]"},
    // enums, names
    {R"({"camera": {"projection": "fisheye"}})",
     {},
     "camera.projection: unknown value \"fisheye\" (allowed: orthographic, perspective)"},
    {R"({"render": {"pipeline": "pathtrace"}})",
     {},
     "render.pipeline: unknown value \"pathtrace\" (allowed: zbuffer, raycast, raytrace)"},
    {R"({"render": {"model": "blinn"}})",
     {},
     "render.model: unknown value \"blinn\" (allowed: lambert, phong)"},
    {R"({"image": {"encoding": "gamma"}})",
     {},
     "image.encoding: unknown value \"gamma\" (allowed: linear, srgb)"},
    {R"({"render": {"accel": "kdtree"}})",
     {},
     "render.accel: unknown value \"kdtree\" (allowed: bvh, none)"},
    {R"({"render": {"antialias": {"mode": "msaa"}}})",
     {},
     "render.antialias.mode: unknown value \"msaa\" (allowed: none, grid, adaptive)"},
    {R"({"render": {"antialias": {"filter": "gauss"}}})",
     {},
     "render.antialias.filter: unknown value \"gauss\" (allowed: box, tent)"},
    {R"({"objects": [{"type": "cube"}]})", {}, "objects.0.type: unknown value \"cube\""},
    {R"({"objects": [{"type": "sphere", "material": "marble"}]})",
     {},
     "objects.0.material: unknown material \"marble\""},
    {R"({"materials": {"gold": {"reflectance": "fresnel"}}})",
     {},
     "materials.gold.reflectance: unknown value \"fresnel\" (allowed: constant, schlick)"},
    {R"({"objects": [{"type": "sphere", "material": {"reflectance": true}}]})",
     {},
     "objects.0.material.reflectance: expected one of constant, schlick, got"},
    {R"({"materials": {"m": {"preset": "marble"}}})",
     {},
     "materials.m.preset: unknown preset \"marble\""},
    {R"({"objects": [{"type": "sphere", "material": 3}]})",
     {},
     "objects.0.material: expected a material name or a material object"},
    {R"({"objects": [{"type": "sphere", "material": {"kd": 2}}]})",
     {},
     "objects.0.material.kd: must be in [0, 1], got 2"},
    // geometry
    {R"({"objects": [{"type": "triangle", "vertices": [[0,0,0],[1,1,1],[2,2,2]]}]})",
     {},
     "objects.0.vertices: degenerate triangle (zero area)"},
    {R"({"objects": [{"type": "triangle", "vertices": [[0,0,0],[1,1,1]]}]})",
     {},
     "objects.0.vertices: expected an array of 3 points"},
    {R"({"objects": [{"type": "sphere", "transform": {"scale": [1, 0, 1]}}]})",
     {},
     "objects.0.transform.scale: components must be non-zero"},
    {R"({"objects": [{"type": "sphere", "transform": {"scale": 0}}]})",
     {},
     "objects.0.transform.scale: components must be non-zero"},
    {R"({"objects": [{"type": "mesh", "file": "x.obj", "smoth": true}]})",
     {},
     "objects.0.smoth: unknown key (known: type, file, smooth, material, transform)"},
    {R"({"objects": [{"type": "mesh", "file": "x.obj"}]})",
     {},
     "scenes/a.json: objects.0.file: cannot read scenes/x.obj: No such file or directory"},
    // overrides
    {R"({"objects": [{"type": "sphere"}]})",
     {"objects.0.radius=abc"},
     "--set objects.0.radius=abc: expected a number, got string \"abc\""},
    {R"({"materials": {"red": {"kd": 0.8}}})",
     {"materials.red.reflectance=fresnel"},
     "--set materials.red.reflectance=fresnel: unknown value \"fresnel\" (allowed: constant, "
     "schlick)"},
    {R"({"objects": [{"type": "sphere"}]})",
     {"objects.0.radius=-2"},
     "--set objects.0.radius=-2: must be > 0, got -2"},
    {R"({"objects": [{"type": "sphere"}]})",
     {"objects.0.colour=1"},
     "--set objects.0.colour=1: unknown key"},
    {R"({"objects": [{"type": "sphere"}]})",
     {"objects.2.radius=1"},
     "--set objects.2.radius=1: index 2 is past the end of objects (size 1"},
    {R"({"objects": [{"type": "sphere", "radius": 1}]})",
     {"objects.0.radius.x=1"},
     "--set objects.0.radius.x=1: objects.0.radius is 1, not an object or array"},
    {R"({"objects": [{"type": "sphere"}]})",
     {"objects.first.radius=1"},
     "--set objects.first.radius=1: objects is an array"},
    {R"({"objects": [{"type": "sphere"}]})",
     {"objects.1.radius=1"},
     "--set objects.1.radius=1: objects.1: missing key \"type\""},
    {R"({"objects": [{"type": "box"}]})",
     {"objects.0.min=[1,1,1]"},
     "--set objects.0.min=[1,1,1]: objects.0.max: must be greater than min"},
    {R"({"image": {"width": 65536}})", {"image.height=65536"}, "--set image.height=65536: image:"},
    {R"({})", {"camera.foo.bar=1"}, "--set camera.foo.bar=1: camera.foo: unknown key"},
    {R"({"objects": [{"type": "sphere", "radius": 2}]})",
     {"objects.0.type=box"},
     "--set objects.0.type=box: objects.0.radius: unknown key"},
    {R"({"objects": [{"type": "sphere", "colour": 2}]})",
     {"objects.0.radius=3"},
     "scenes/a.json: objects.0.colour: unknown key"},
};

INSTANTIATE_TEST_SUITE_P(Messages, BadScene, ::testing::ValuesIn(kBadCases));

TEST(SceneLoader, MalformedSetArguments) {
    struct Case {
        const char* arg;
        const char* expected;
    };
    const Case cases[] = {
        {"objects.0.radius", "--set objects.0.radius: expected PATH=JSON"},
        {"=2", "--set =2: empty key path"},
        {"objects..radius=2", "--set objects..radius=2: empty segment"},
        {"objects.0.=2", "--set objects.0.=2: empty segment"},
        {"objects.0.radius=[1,", "--set objects.0.radius=[1,: JSON syntax error"},
        {"objects.0.radius=", "--set objects.0.radius=: JSON syntax error"},
        {"objects.0.radius=1e999", "--set objects.0.radius=1e999: number out of range"},
        {"objects.0.radius=two words", "--set objects.0.radius=two words: JSON syntax error"},
    };
    for (const Case& c : cases) {
        try {
            parse_set(c.arg);
            ADD_FAILURE() << "accepted: " << c.arg;
        } catch (const InputError& e) {
            EXPECT_THAT(e.what(), HasSubstr(c.expected));
        }
    }
}

TEST(SceneLoader, ErrorsInTheFileAreNotBlamedOnUnrelatedOverrides) {
    try {
        parse(R"({"objects": [{"type": "sphere", "radius": -1}, {"type": "sphere"}]})",
              sets({"objects.1.radius=2"}));
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()), "scenes/a.json: objects.0.radius: must be > 0, got -1");
    }
}

TEST(SceneLoader, OtherOptionsNameThemselves) {
    try {
        parse(R"({})", {Override{"image.width", "0", "--width"}});
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()), "--width 0: image.width: must be in [1, 65536], got 0");
    }
}

}  // namespace
}  // namespace luz
