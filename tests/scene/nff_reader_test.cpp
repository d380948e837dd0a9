// Tests of NFF scenes (docs/SCENES.md#nff): each statement against the description worked out by
// hand, the settings an NFF file implies, polygons as meshes, and FILE:LINE messages for bad input.
#include "scene/nff_reader.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <fstream>
#include <sstream>

#include "scene/nff_statements.h"
#include "scene/scene_loader.h"
#include "scene/scene_writer.h"

namespace luz {
namespace {

using ::testing::EndsWith;
using ::testing::HasSubstr;

const std::string kView = "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 1\nresolution 4 3\n";

SceneDesc load(const std::string& body, const std::vector<Override>& overrides = {}) {
    return parse_scene(kView + body, "dir/t.nff", "dir", overrides);
}

/// The message loading `text` (the whole file) gives, or "(no error)".
std::string nff_error_of(const std::string& text, const std::vector<Override>& overrides = {}) {
    try {
        parse_scene(text, "dir/t.nff", "dir", overrides);
    } catch (const InputError& e) {
        return e.what();
    }
    return "(no error)";
}

void expect_rgb(const Rgb& c, float r, float g, float b) {
    EXPECT_NEAR(c.x, r, 1e-6f);
    EXPECT_NEAR(c.y, g, 1e-6f);
    EXPECT_NEAR(c.z, b, 1e-6f);
}

double nff_triangle_area(const MeshData& m, size_t t) {
    const Vec3 a = m.positions[m.position[3 * t]], b = m.positions[m.position[3 * t + 1]],
               c = m.positions[m.position[3 * t + 2]];
    return 0.5 * double(length(cross(b - a, c - a)));
}

double mesh_area(const MeshData& m) {
    double s = 0;
    for (size_t t = 0; t < m.triangle_count(); ++t) s += nff_triangle_area(m, t);
    return s;
}

TEST(NffReader, NameEndsInNff) {
    EXPECT_TRUE(loader::is_nff_file("a/balls.nff"));
    EXPECT_TRUE(loader::is_nff_file("BALLS.NFF"));
    EXPECT_FALSE(loader::is_nff_file("balls.json"));
    EXPECT_FALSE(loader::is_nff_file("nff"));
}

TEST(NffReader, ViewpointIsAPerspectiveCameraWithFovFromAngle) {
    const SceneDesc d = load("b 0.1 0.2 0.3\n");
    EXPECT_EQ(d.camera.projection, Projection::perspective);
    EXPECT_EQ(d.camera.position, Vec3(0, 0, 5));
    EXPECT_EQ(d.camera.look_at, Vec3(0, 0, 0));
    EXPECT_EQ(d.camera.up, Vec3(0, 1, 0));
    // angle 45 between the centres of rows 0 and 2 of 3: 2·atan(tan(22.5°)·3/2) = 63.70705°
    EXPECT_NEAR(d.camera.fov_y, 63.70705f, 1e-4f);
    EXPECT_EQ(d.image.width, 4);
    EXPECT_EQ(d.image.height, 3);
    expect_rgb(d.image.background, 0.1f, 0.2f, 0.3f);
    EXPECT_EQ(d.name, "t");
}

TEST(NffReader, BackgroundIsBlackByDefaultAndMayPrecedeTheViewpoint) {
    expect_rgb(load("").image.background, 0, 0, 0);
    const SceneDesc d = parse_scene("# comment\nb 1 0 0\n" + kView, "t.nff", "");
    expect_rgb(d.image.background, 1, 0, 0);
}

TEST(NffReader, ImpliedSettings) {
    const SceneDesc d = load("l 1 2 3\n");
    EXPECT_EQ(d.render.pipeline, Pipeline::raytrace);
    EXPECT_EQ(d.render.model, Model::phong);
    EXPECT_EQ(d.render.max_depth, 4);
    EXPECT_FALSE(d.render.tree_attenuation);
    EXPECT_EQ(d.render.min_weight, 0.0f);
    EXPECT_EQ(d.attenuation, Attenuation::none);
    // one light: Ia = √1/(2·1) = 0.5
    expect_rgb(d.ambient, 0.5f, 0.5f, 0.5f);
}

TEST(NffReader, LightsWithoutColourHaveIntensityOneOverRootL) {
    const SceneDesc d = load("l 1 2 3\nl -1 0 0 0.5 0.25 1\nl 0 4 0\n");
    ASSERT_EQ(d.lights.size(), 3u);
    EXPECT_EQ(d.lights[0].position, Vec3(1, 2, 3));
    const float third = 0.57735027f;  // 1/√3
    expect_rgb(d.lights[0].intensity, third, third, third);
    expect_rgb(d.lights[1].intensity, 0.5f, 0.25f, 1);
    expect_rgb(d.lights[2].intensity, third, third, third);
    EXPECT_EQ(d.lights[1].radius, 0.0f);
    const float Ia = 0.28867513f;  // √3/(2·3)
    expect_rgb(d.ambient, Ia, Ia, Ia);
}

TEST(NffReader, MaterialsAreSharedByIdenticalLinesAndNamedInOrder) {
    const SceneDesc d = load(
        "f 1 0.5 0.2 0.8 0.3 20 0.4 0.9\ns 0 0 0 1\n"
        "f 0 1 0 1 0 100000 0 1.5\ns 1 0 0 1\n"
        "f 1.0 0.5 0.20 0.8 0.3 20 0.4 0.9\ns 2 0 0 -1\n");
    // the default material, then f1 and f2
    ASSERT_EQ(d.materials.size(), 3u);
    const Material& f1 = d.materials[1];
    EXPECT_EQ(f1.name, "f1");
    expect_rgb(f1.kd, 0.8f, 0.4f, 0.16f);  // Kd·(r, g, b)
    expect_rgb(f1.ka, 0.8f, 0.4f, 0.16f);
    expect_rgb(f1.ks, 0.3f, 0.3f, 0.3f);
    EXPECT_FLOAT_EQ(f1.reflection, 0.3f);
    EXPECT_FLOAT_EQ(f1.n, 20);
    EXPECT_FLOAT_EQ(f1.transparency, 0.4f);
    EXPECT_FLOAT_EQ(f1.ior, 1.0f);  // 0.9 reads as 1
    EXPECT_EQ(d.materials[2].name, "f2");
    EXPECT_FLOAT_EQ(d.materials[2].ior, 1.5f);
    EXPECT_FLOAT_EQ(d.materials[2].n, 100000);
    ASSERT_EQ(d.objects.size(), 3u);
    EXPECT_EQ(d.objects[0].material, 1);
    EXPECT_EQ(d.objects[1].material, 2);
    EXPECT_EQ(d.objects[2].material, 1);  // the same numbers: f1 again
}

TEST(NffReader, SetReachesAMaterialByName) {
    const SceneDesc d =
        load("f 1 1 1 1 0 1 0 1\ns 0 0 0 1\n", {{"materials.f1.kd", "[0.1, 0.2, 0.3]"}});
    expect_rgb(d.materials[1].kd, 0.1f, 0.2f, 0.3f);
    expect_rgb(d.materials[1].ka, 1, 1, 1);
    const SceneDesc w = load("", {{"image.width", "64", "--width"}});
    EXPECT_EQ(w.image.width, 64);
    EXPECT_EQ(w.image.height, 3);
}

TEST(NffReader, SpheresTakeTheAbsoluteRadius) {
    const SceneDesc d = load("s 1 2 3 -0.5\n");
    ASSERT_EQ(d.objects.size(), 1u);
    EXPECT_EQ(d.objects[0].type, ShapeType::sphere);
    EXPECT_EQ(d.objects[0].center, Vec3(1, 2, 3));
    EXPECT_FLOAT_EQ(d.objects[0].radius, 0.5f);
    EXPECT_EQ(d.objects[0].material, 0);  // before any f: the default material
}

TEST(NffReader, EqualRadiiMakeAnOpenCylinderOnOneLineOrThree) {
    for (const std::string c : {"c 0 0 1 0.5 0 0 4 -0.5\n", "c\n0 0 1 0.5\n0 0 4 -0.5\n"}) {
        const SceneDesc d = load(c);
        ASSERT_EQ(d.objects.size(), 1u) << c;
        const ObjectDesc& o = d.objects[0];
        EXPECT_EQ(o.type, ShapeType::cylinder);
        EXPECT_EQ(o.base, Vec3(0, 0, 1));
        EXPECT_EQ(o.axis, Vec3(0, 0, 1));
        EXPECT_FLOAT_EQ(o.height, 3);
        EXPECT_FLOAT_EQ(o.radius, 0.5f);
        EXPECT_FALSE(o.caps);
    }
}

TEST(NffReader, UnequalRadiiMakeAnOpenFrustumWiderEndAsBase) {
    // base radius 0.2 at z = 1, apex radius 0.5 at z = 3: the wider end becomes the base
    for (const std::string c : {"c 0 0 1 0.2 0 0 3 0.5\n", "c 0 0 3 -0.5 0 0 1 0.2\n"}) {
        const SceneDesc d = load(c);
        ASSERT_EQ(d.objects.size(), 1u) << c;
        const ObjectDesc& o = d.objects[0];
        EXPECT_EQ(o.type, ShapeType::cone);
        EXPECT_EQ(o.base, Vec3(0, 0, 3));
        EXPECT_EQ(o.axis, Vec3(0, 0, -1));
        EXPECT_FLOAT_EQ(o.height, 2);
        EXPECT_FLOAT_EQ(o.radius, 0.5f);
        EXPECT_FLOAT_EQ(o.apex_radius, 0.2f);
        EXPECT_FALSE(o.caps);
    }
    const SceneDesc pointed = load("c\n0 0 0 1\n0 4 0 0\n");
    EXPECT_EQ(pointed.objects.at(0).type, ShapeType::cone);
    EXPECT_EQ(pointed.objects[0].base, Vec3(0, 0, 0));
    EXPECT_EQ(pointed.objects[0].axis, Vec3(0, 1, 0));
    EXPECT_FLOAT_EQ(pointed.objects[0].apex_radius, 0);
}

TEST(NffReader, PolygonsOfOneMaterialFormOneFlatMesh) {
    const SceneDesc d = load(
        "f 1 0 0 1 0 1 0 1\np 3\n0 0 0\n1 0 0\n0 1 0\n"
        "p 4\n0 0 1\n2 0 1\n2 2 1\n0 2 1\n"
        "f 0 1 0 1 0 1 0 1\np 3\n0 0 2\n1 0 2\n0 1 2\n"
        "f 1 0 0 1 0 1 0 1\np 3\n0 0 3\n1 0 3\n0 1 3\n");
    ASSERT_EQ(d.objects.size(), 2u);
    const ObjectDesc& red = d.objects[0];
    EXPECT_EQ(red.type, ShapeType::mesh);
    EXPECT_EQ(red.material, 1);
    EXPECT_FALSE(red.smooth);
    ASSERT_TRUE(red.mesh);
    EXPECT_EQ(red.mesh->triangle_count(), 4u);  // 1 + 2 + 1
    EXPECT_DOUBLE_EQ(mesh_area(*red.mesh), 0.5 + 4 + 0.5);
    EXPECT_EQ(d.objects[1].material, 2);
    EXPECT_EQ(d.objects[1].mesh->triangle_count(), 1u);
}

TEST(NffReader, ConcavePolygonIsCoveredExactly) {
    // A comb: a fan from its first corner would cover the gaps between the teeth.
    const std::string comb = "p 8\n0 0 0\n5 0 0\n5 3 0\n4 3 0\n4 1 0\n1 1 0\n1 3 0\n0 3 0\n";
    const SceneDesc d = load(comb);
    const MeshData& m = *d.objects.at(0).mesh;
    EXPECT_EQ(m.triangle_count(), 6u);
    EXPECT_NEAR(mesh_area(m), 5 * 1 + 2 * 1 * 2, 1e-9);  // the base and two teeth
    for (size_t t = 0; t < m.triangle_count(); ++t) {
        Vec3 c{0.0f};
        for (int k = 0; k < 3; ++k) c += m.positions[m.position[3 * t + k]] / 3.0f;
        const bool in_base = c.y < 1, in_tooth = c.x < 1 || c.x > 4;
        EXPECT_TRUE(in_base || in_tooth) << "triangle " << t << " centre " << c.x << " " << c.y;
    }
}

TEST(NffReader, PatchesKeepTheirNormalsForInterpolation) {
    const SceneDesc d = load(
        "pp 3\n0 0 0 0 0 1\n1 0 0 0 0.6 0.8\n0 1 0 0.6 0 0.8\n"
        "p 3\n0 0 1\n1 0 1\n0 1 1\n");
    ASSERT_EQ(d.objects.size(), 1u);
    const ObjectDesc& o = d.objects[0];
    EXPECT_TRUE(o.smooth);
    const MeshData& m = *o.mesh;
    ASSERT_EQ(m.triangle_count(), 2u);
    for (int k = 0; k < 3; ++k) {
        ASSERT_GE(m.normal[k], 0);
        EXPECT_EQ(m.positions[m.position[k]], m.positions[m.position[k]]);
    }
    EXPECT_EQ(m.normals[m.normal[1]], Vec3(0, 0.6f, 0.8f));
    EXPECT_EQ(m.positions[m.position[1]], Vec3(1, 0, 0));
    for (int k = 3; k < 6; ++k) EXPECT_EQ(m.normal[k], -1);  // the p polygon: flat
}

TEST(NffReader, GearsConcavePolygonsAreCoveredExactly) {
    // Every polygon of the SPD's gears (concave 144-gons among them): the meshes' area is the
    // polygons' (Newell) area; a fan would add the overlaps of its flipped triangles.
    const std::string path = std::string(LUZ_SOURCE_DIR) + "/scenes/spd/gears.nff";
    std::ifstream in(path);
    ASSERT_TRUE(in) << path;
    std::stringstream text;
    text << in.rdbuf();
    const SceneDesc d = parse_scene(text.str(), path, "");
    double meshes = 0;
    for (const ObjectDesc& o : d.objects) {
        if (o.mesh) meshes += mesh_area(*o.mesh);
    }
    std::istringstream lines(text.str());
    std::string line;
    double polygons = 0;
    int big = 0;
    while (std::getline(lines, line)) {
        if (line.rfind("p ", 0) != 0) continue;
        const int n = std::stoi(line.substr(2));
        big += n == 144;
        std::vector<Vec3> p(n);
        for (Vec3& v : p) {
            std::getline(lines, line);
            std::istringstream(line) >> v.x >> v.y >> v.z;
        }
        Vec3 newell{0.0f};
        for (int i = 0; i < n; ++i) newell += cross(p[i], p[(i + 1) % n]);
        polygons += 0.5 * double(length(newell));
    }
    EXPECT_EQ(big, 128);
    EXPECT_NEAR(meshes, polygons, 1e-4 * polygons);
}

TEST(NffReader, BadInputNamesTheLine) {
    const std::string v = kView;  // lines 1–7
    const std::vector<std::pair<std::string, std::string>> cases = {
        {v + "s 0 0 0\n", "dir/t.nff:8: s: expected 4 numbers, got 3"},
        {v + "s 0 0 0 1 2\n", "dir/t.nff:8: s: expected at most 4 numbers"},
        {v + "s 0 0 x 1\n", "dir/t.nff:8: s: malformed number \"x\""},
        {v + "s 0 0 nan 1\n", "dir/t.nff:8: s: "},
        {v + "s 0 0 1e39 1\n", "dir/t.nff:8: s: number out of"},
        {v + "\n# c\nsphere 0 0 0 1\n", "dir/t.nff:10: unknown statement \"sphere\""},
        {v + "p 2\n0 0 0\n1 0 0\n", "dir/t.nff:8: p: a polygon needs at least 3 vertices, got 2"},
        {v + "p 2.5\n", "dir/t.nff:8: p: expected a whole number of vertices, got 2.5"},
        // counts beyond a float's 2²⁴ read exactly, whole numbers shown whole
        {v + "p 999999999\n",
         "dir/t.nff:8: p: a polygon may have at most 100000000 vertices, got 999999999"},
        {v + "pp 2147483647\n",
         "dir/t.nff:8: pp: a polygon may have at most 100000000 vertices, got 2147483647"},
        {v + "p 16777217\n0 0 0\n",
         "dir/t.nff:8: p: the file ends before its 16777217 vertices (it has 1)"},
        {v + "p 1e3\n0 0 0\n", "dir/t.nff:8: p: the file ends before its 1000 vertices"},
        {v + "p 4\n0 0 0\n1 0 0\n",
         "dir/t.nff:8: p: the file ends before its 4 vertices (it has 2)"},
        {v + "pp 3\n0 0 0 0 0 1\n1 0 0\n", "dir/t.nff:10: pp vertex (x y z nx ny nz): expected 6"},
        {v + "c\n0 0 0 1\n", "dir/t.nff:8: c: the file ends before its apex line"},
        {v + "c 0 0 0 1 0 0 1\n", "dir/t.nff:8: c: expected 8 numbers"},
        {v + "c 0 0 0 1 0 0 0 1\n", "dir/t.nff:8: c: base and apex must be distinct"},
        {v + "l 0 0 0 1\n", "dir/t.nff:8: l: expected 3 numbers (x y z) or 6"},
        {v + "f 1 1 1 1 0 1 0\n", "dir/t.nff:8: f: expected 8 numbers, got 7"},
        {v + "b 0 0\n", "dir/t.nff:8: b: expected 3 numbers, got 2"},
        {v + v, "dir/t.nff:8: v: a second viewpoint (the first is at line 1)"},
        {"s 0 0 0 1\n" + v, "dir/t.nff:1: s: before \"v\""},
        {"b 0 0 0\n", "dir/t.nff:1: no \"v\" statement"},
        {"", "dir/t.nff:1: no \"v\" statement"},
        {"v\nfrom 0 0 5\nup 0 1 0\n", "dir/t.nff:3: v: expected \"at\" here"},
        {"v\nfrom 0 0 5\nat 0 0 0\n", "dir/t.nff:1: v: the file ends before its \"up\" line"},
        {"v x\n", "dir/t.nff:1: v: expected nothing after \"v\""},
        {"v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 180\nhither 1\nresolution 4 3\n",
         "dir/t.nff:5: angle: must be in (0, 180) degrees, got 180"},
        {"v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 1\nresolution 4.5 3\n",
         "dir/t.nff:7: resolution: expected two whole numbers in [1, 65536], got 4.5 3"},
        // checks of the description land on the line the key came from
        {v + "s 0 0 0 0\n", "dir/t.nff:8: objects.0.radius: must be > 0, got 0"},
        {"v\nfrom 0 0 5\nat 0 0 0\nup 0 0 1\nangle 45\nhither 1\nresolution 4 3\n",
         "dir/t.nff:4: camera.up: must not be parallel"},
        {v + "f 2 1 1 1 0 1 0 1\n", "dir/t.nff:8: materials.f1.ka: "},
        {v + "l 0 0 0 -1 0 0\n", "dir/t.nff:8: lights.0.intensity: "},
        // values read into floats shown as written, not as the double nearest the float
        {"v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 1\nresolution 100000 3\n",
         "dir/t.nff:7: resolution: expected two whole numbers in [1, 65536], got 100000 3"},
    };
    for (const auto& [text, message] : cases) {
        const std::string e = nff_error_of(text);
        EXPECT_THAT(e, HasSubstr(message)) << text;
        EXPECT_EQ(e.find('\n'), std::string::npos) << e;
    }  // a value read into a float shown as written, not as the double nearest that float
    EXPECT_THAT(nff_error_of(v + "f 1 0 0 0.8 -0.2 10 0 1\n"),
                EndsWith("dir/t.nff:8: materials.f1.ks: must be in [0, 1], got -0.2"));
}

/// Every statement kind, objects before the first `f` and after a material comes back.
const std::string kEveryObject = kView +
                                 "s 5 5 5 1\n"
                                 "f 1 0 0 1 0 1 0 1\n"
                                 "s 0 0 0 -1\n"
                                 "c 0 0 0 1 0 1 0 1\n"
                                 "c\n0 0 0 1\n0 1 1 0.5\n"
                                 "f 0 1 0 0.5 0.5 20 0.3 1.5\n"
                                 "c 0 2 0 0.5 0 0 0 1\n"
                                 "p 3\n0 0 0\n1 0 0\n0 1 0\n"
                                 "s 1 1 1 0.5\n"
                                 "f 1 0 0 1 0 1 0 1\n"
                                 "pp 3\n0 0 1 0 0 1\n1 0 1 0 0 1\n0 1 1 0 0 1\n"
                                 "c 3 3 3 0.25 3 3 4 0\n";

// Spheres, cylinders and cones skip the document (NffScene::direct) in an order list beside
// its objects, which are then the meshes alone.
TEST(NffReader, DirectReadingKeepsTheObjectsOrder) {
    const loader::NffScene nff = loader::read_nff(kEveryObject, "dir/t.nff", "dir", true);
    ASSERT_TRUE(nff.direct);
    EXPECT_EQ(nff.direct->objects.size(), 7u);
    EXPECT_EQ(nff.doc["objects"].size(), 2u);  // the meshes of f2 and f1
    EXPECT_EQ(nff.direct->order, (std::vector<std::int64_t>{0, 1, 2, 3, 4, -1, 5, -2, 6}));
    EXPECT_EQ(nff.direct->materials,
              (std::vector<std::string>{"", "f1", "f1", "f1", "f2", "f2", "f1"}));
    EXPECT_EQ(nff.object_lines.size(), 9u);
    EXPECT_FALSE(loader::read_nff(kEveryObject, "dir/t.nff", "dir").direct);
}

// Read directly or through the document (as when an override reaches into the objects), the
// scene is the same, object for object, on every SPD scene and on a file of every statement.
TEST(NffReader, ReadDirectlyTheSceneIsTheDocumentsOwn) {
    std::vector<std::pair<std::string, std::string>> files = {{"dir/t.nff", kEveryObject}};
    for (const char* name : {"balls", "gears", "mount", "rings", "teapot", "tetra", "tree"}) {
        const std::string path = std::string(LUZ_SOURCE_DIR) + "/scenes/spd/" + name + ".nff";
        std::ifstream in(path);
        std::stringstream text;
        text << in.rdbuf();
        files.push_back({path, text.str()});
    }
    for (const auto& [label, text] : files) {
        const SceneDesc direct = parse_scene(text, label, "dir", {});
        ASSERT_FALSE(direct.objects.empty());
        const std::string type(shape_name(direct.objects[0].type));
        const SceneDesc doc =
            parse_scene(text, label, "dir", {{"objects.0.type", '"' + type + '"'}});
        ASSERT_EQ(direct.objects.size(), doc.objects.size()) << label;
        for (size_t i = 0; i < doc.objects.size(); ++i) {
            ObjectDesc a = direct.objects[i], b = doc.objects[i];
            ASSERT_EQ(bool(a.mesh), bool(b.mesh)) << label << " " << i;
            if (a.mesh) {  // two reads, two meshes: the same triangles
                EXPECT_EQ(a.mesh->positions, b.mesh->positions) << label << " " << i;
                EXPECT_EQ(a.mesh->position, b.mesh->position) << label << " " << i;
                EXPECT_EQ(a.mesh->normals, b.mesh->normals) << label << " " << i;
                a.mesh = b.mesh = nullptr;
            }
            ASSERT_TRUE(a == b) << label << " " << i << " " << a.path;
        }
        EXPECT_EQ(scene_to_json(direct, "dir"), scene_to_json(doc, "dir")) << label;
    }
}

// An object the document would refuse is read through it, for its message: the same as ever.
TEST(NffReader, ReadDirectlyABadObjectGetsTheDocumentsMessage) {
    const std::vector<std::pair<std::string, std::string>> cases = {
        {kView + "s 0 0 0 1\ns 0 0 0 1e-50\n", "dir/t.nff:9: objects.1.radius: must be > 0"},
        {kView + "s 0 0 0 1\nc 0 0 0 1e-50 0 1 0 1e-50\n",
         "dir/t.nff:9: objects.1.radius: must be > 0"},
        {kView + "c 0 0 0 1 3e38 3e38 0 0.5\n",
         "dir/t.nff:8: objects.0.height: must be a finite number (a float"},
    };
    for (const auto& [text, message] : cases) {
        EXPECT_THROW(loader::read_nff(text, "dir/t.nff", "dir", true), loader::NffNotDirect);
        EXPECT_THAT(nff_error_of(text), HasSubstr(message)) << text;
    }
}

TEST(NffReader, AnOverrideIsBlamedForWhatItPutThere) {
    EXPECT_THAT(nff_error_of(kView + "f 1 1 1 1 0 1 0 1\n", {{"materials.f1.n", "-1"}}),
                HasSubstr("--set materials.f1.n=-1"));
}

}  // namespace
}  // namespace luz

TEST(NffStatements, ShapeLinesCountTheLinesStartingWithSOrC) {
    using luz::loader::nff_text::shape_lines;
    EXPECT_EQ(shape_lines(""), 0u);
    EXPECT_EQ(shape_lines("s 0 0 0 1"), 1u);  // a last line without a newline counts
    // the reader's estimate of its objects: s and c lines, not v, p, f, comments or blank lines
    EXPECT_EQ(shape_lines("v\nfrom 0 0 1\ns 0 0 0 1\n# s\n\nc\n0 0 0 1\n1 1 1 1\n"
                          "p 3\n0 0 0\n1 0 0\n0 1 0\ns 1 1 1 1\n"),
              3u);
    EXPECT_EQ(shape_lines("s 0 0 0 1\r\nc\r\n"), 2u);
}
