// BuiltScene writer round trip: load → save → load gives the same description (the same JSON when
// saved again) and the same image bits; meshes keep their files.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "render/render.h"
#include "scene/scene_loader.h"
#include "scene/scene_writer.h"

namespace luz {
namespace {

namespace fs = std::filesystem;

struct TempFolder {
    fs::path path;
    TempFolder() {
        const auto* info = testing::UnitTest::GetInstance()->current_test_info();
        path = fs::temp_directory_path() /
               ("luz_round_trip_" + std::to_string(::getpid()) + "_" + info->name());
        fs::remove_all(path);
        fs::create_directories(path);
    }
    ~TempFolder() {
        std::error_code ec;
        fs::remove_all(path, ec);
    }
};

Image render_of(const SceneDesc& d) {
    RenderStats stats;
    return render(build_scene(d), d, RenderControl{}, stats);
}

void expect_round_trip(const std::string& source, const std::vector<Override>& overrides,
                       const fs::path& dir) {
    const SceneDesc a = load_scene(source, overrides);
    const std::string saved = (dir / "saved.json").string();
    write_scene(saved, a);
    const SceneDesc b = load_scene(saved);
    EXPECT_EQ(scene_to_json(a, dir.string()), scene_to_json(b, dir.string())) << source;
    const Image ia = render_of(a), ib = render_of(b);
    ASSERT_EQ(ia.pixels.size(), ib.pixels.size());
    EXPECT_TRUE(ia.pixels == ib.pixels) << source << ": the same image bits";
}

TEST(SceneRoundTrip, BuiltInScenes) {
    TempFolder t;
    const std::vector<Override> small = {{"image.width", "96"}, {"image.height", "72"}};
    for (const char* s : {"demo:primitives", "demo:whitted", "demo:materials"})
        expect_round_trip(s, small, t.path);
}

TEST(SceneRoundTrip, EditedValuesTransformsAndSettings) {
    TempFolder t;
    const std::vector<Override> edits = {
        {"image.width", "80"},
        {"image.height", "60"},
        {"materials.blue.n", "3.7"},
        {"materials.blue.kd", "[0.1, 0.2, 0.3]"},
        {"ambient", "[0.3, 0.2, 0.1]"},
        {"attenuation_k", "2.5"},
        {"lights.0.intensity", "[1.5, 1, 0.5]"},
        {"render.pipeline", "\"raytrace\""},
        {"render.tree_attenuation", "true"},
        {"render.antialias.mode", "\"grid\""},
        {"render.antialias.samples", "9"},
        {"objects.1.transform", R"({"scale": [1, 2, 0.5], "rotate": [10, 20, 30],
                                   "translate": [0.1, 0.2, 0.3]})"},
        {"objects.2.material", R"({"preset": "vidro", "ior": 1.7})"},
        {"materials.yellow.reflectance", "\"schlick\""}};
    expect_round_trip("demo:primitives", edits, t.path);
}

TEST(SceneRoundTrip, FrustumKeepsItsApexRadius) {
    // demo:primitives' cone (objects.4) made a truncated cone (docs/SCENES.md#scene-files:
    // apex_radius)
    TempFolder t;
    const std::vector<Override> edits = {
        {"image.width", "80"}, {"image.height", "60"}, {"objects.4.apex_radius", "0.2"}};
    expect_round_trip("demo:primitives", edits, t.path);
    const SceneDesc a = load_scene("demo:primitives", edits);
    ASSERT_EQ(a.objects[4].type, ShapeType::cone);
    EXPECT_FLOAT_EQ(a.objects[4].apex_radius, 0.2f);
    const std::string saved = (t.path / "frustum.json").string();
    write_scene(saved, a);
    EXPECT_FLOAT_EQ(load_scene(saved).objects[4].apex_radius, 0.2f);
    // a full cone is written with apex_radius 0 and read back as one
    EXPECT_EQ(load_scene("demo:primitives").objects[4].apex_radius, 0.0f);
}

TEST(SceneRoundTrip, ReflectanceIsWrittenBack) {
    // docs/SCENES.md#reflectance: a saved scene keeps each material's curve, the metal presets'
    // schlick included.
    TempFolder t;
    const SceneDesc a =
        load_scene("demo:materials", {{"materials.floor.reflectance", "\"schlick\""}});
    const std::string saved = (t.path / "saved.json").string();
    write_scene(saved, a);
    const SceneDesc b = load_scene(saved);
    ASSERT_EQ(a.materials.size(), b.materials.size());
    int schlick = 0;
    for (size_t i = 0; i < a.materials.size(); ++i) {
        EXPECT_EQ(a.materials[i].reflectance, b.materials[i].reflectance) << a.materials[i].name;
        schlick += b.materials[i].reflectance == Reflectance::schlick;
    }
    EXPECT_EQ(schlick, 4);  // the floor, ouro, prata and cobre
}

TEST(SceneRoundTrip, MeshFilesRelativeToTheSavedScene) {
    TempFolder t;
    fs::create_directories(t.path / "in" / "meshes");
    fs::create_directories(t.path / "out");
    std::ofstream(t.path / "in" / "meshes" / "tet.obj")
        << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    std::ofstream(t.path / "in" / "scene.json")
        << R"({"image": {"width": 40, "height": 30}, "render": {"pipeline": "raytrace"},
              "objects": [{"type": "mesh", "file": "meshes/tet.obj",
                           "transform": {"scale": 2, "rotate": [0, 45, 0]}}]})";
    const SceneDesc a = load_scene((t.path / "in" / "scene.json").string());
    const fs::path saved = t.path / "out" / "saved.json";
    write_scene(saved.string(), a);
    std::ifstream f(saved);
    const std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("\"../in/meshes/tet.obj\""), std::string::npos) << text;
    const SceneDesc b = load_scene(saved.string());
    EXPECT_TRUE(render_of(a).pixels == render_of(b).pixels);
}

TEST(SceneRoundTrip, BuiltInMeshIsWrittenNextToTheScene) {
    TempFolder t;
    const SceneDesc a = load_scene("demo:bunny", {{"image.width", "48"}, {"image.height", "36"}});
    write_scene((t.path / "bunny_scene.json").string(), a);
    EXPECT_TRUE(fs::exists(t.path / "bunny.obj"));
    const SceneDesc b = load_scene((t.path / "bunny_scene.json").string());
    EXPECT_TRUE(render_of(a).pixels == render_of(b).pixels);
}

TEST(SceneRoundTrip, NffPolygonsAreWrittenAsObjFilesThatReload) {
    // An NFF file's polygons are meshes held in memory ("FILE#MATERIAL"): saving the scene
    // writes each as an OBJ file beside it, bit for bit, never over a different file.
    TempFolder t;
    fs::create_directories(t.path / "in");
    fs::create_directories(t.path / "out");
    std::ofstream(t.path / "in" / "poly.nff")
        << "v\nfrom 0.3 0.4 6\nat 0 0 0\nup 0 1 0\nangle 40\nhither 1\nresolution 48 36\n"
           "b 0.1 0.2 0.3\nl 4 5 6\n"
           "f 0.8 0.3 0.2 0.6 0.3 20 0 1\n"
           // a concave polygon (a comb) and a smooth patch
           "p 8\n-2 -1 0\n2 -1 0\n2 1.1 0\n1 1.1 0\n1 0 0\n-1 0 0\n-1 1.1 0\n-2 1.1 0\n"
           "f 0.2 0.5 0.9 0.7 0.2 10 0.3 1.5\n"
           "pp 3\n-1 -1.5 0.5 0 0.6 0.8\n1.3 -1.4 0.4 0.3 0 0.954\n0 1.7 0.6 -0.2 0.3 0.933\n"
           "s 0.3 -0.2 1.2 0.4\n";
    const SceneDesc a = load_scene((t.path / "in" / "poly.nff").string());
    // a different file already has the first mesh's name: it stays as it was
    std::ofstream(t.path / "out" / "poly.nff.f1.obj") << "# mine\n";
    const fs::path saved = t.path / "out" / "saved.json";
    write_scene(saved.string(), a);
    std::ifstream mine(t.path / "out" / "poly.nff.f1.obj");
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(mine), {}), "# mine\n");
    EXPECT_TRUE(fs::exists(t.path / "out" / "poly.nff.f1-2.obj"));
    EXPECT_TRUE(fs::exists(t.path / "out" / "poly.nff.f2.obj"));
    const SceneDesc b = load_scene(saved.string());
    std::ifstream f(saved);
    const std::string text{std::istreambuf_iterator<char>(f), {}};
    EXPECT_NE(text.find("\"poly.nff.f1-2.obj\""), std::string::npos) << text;
    const Image ia = render_of(a), ib = render_of(b);
    EXPECT_TRUE(ia.pixels == ib.pixels) << "the same image bits";
    // saved again into the same folder: the same files, no new ones
    const auto files = [&] {
        return std::distance(fs::directory_iterator(t.path / "out"), fs::directory_iterator{});
    };
    const auto before = files();
    write_scene((t.path / "out" / "again.json").string(), b);
    EXPECT_EQ(files(), before + 1);
    EXPECT_TRUE(render_of(load_scene((t.path / "out" / "again.json").string())).pixels ==
                ia.pixels);
}

}  // namespace
}  // namespace luz
