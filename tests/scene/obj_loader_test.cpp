// Tests of OBJ/MTL loading (docs/SCENES.md#scene-files `mesh`): triangulation, index forms,
// normals, line ends, MTL mapping, warnings, and FILE:LINE messages for bad input.
#include "scene/obj_loader.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>

#include "scene/scene_loader.h"

namespace luz {
namespace {

using ::testing::HasSubstr;

/// Files by path for parse_obj's MTL reader.
struct Files {
    std::map<std::string, std::string> text;
    TextReader reader() const {
        return [this](const std::string& path, std::string& reason) -> std::optional<std::string> {
            const auto it = text.find(path);
            if (it == text.end()) {
                reason = "No such file or directory";
                return std::nullopt;
            }
            return it->second;
        };
    }
};

MeshData parse_test_obj(const std::string& obj, std::vector<std::string>* warnings = nullptr,
                        const Files& files = {}, bool with_materials = true) {
    std::vector<std::string> w;
    MeshData m = parse_obj(obj, "m/x.obj", with_materials, files.reader(), w);
    if (warnings) *warnings = w;
    return m;
}

/// The InputError message parse_test_obj() throws for `obj`.
std::string obj_error_of(const std::string& obj, const Files& files = {}) {
    try {
        parse_test_obj(obj, nullptr, files);
    } catch (const InputError& e) {
        return e.what();
    }
    return "(no error)";
}

double obj_triangle_area(const MeshData& m, size_t t) {
    const Vec3 a = m.positions[m.position[3 * t]], b = m.positions[m.position[3 * t + 1]],
               c = m.positions[m.position[3 * t + 2]];
    return 0.5 * length(cross(b - a, c - a));
}

double total_area(const MeshData& m) {
    double s = 0;
    for (size_t t = 0; t < m.triangle_count(); ++t) s += obj_triangle_area(m, t);
    return s;
}

const char* kSquare = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";

TEST(ObjLoader, ATriangle) {
    const MeshData m = parse_test_obj("# a comment\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    EXPECT_EQ(m.file, "m/x.obj");
    ASSERT_EQ(m.positions.size(), 3u);
    EXPECT_EQ(m.positions[1], (Vec3{1, 0, 0}));
    EXPECT_EQ(m.position, (std::vector<uint32_t>{0, 1, 2}));
    EXPECT_EQ(m.normal, (std::vector<int32_t>{-1, -1, -1}));  // no normals given
    EXPECT_EQ(m.material, (std::vector<int32_t>{-1}));
}

TEST(ObjLoader, QuadsAndNgonsAreTriangulated) {
    const MeshData quad = parse_test_obj(std::string(kSquare) + "f 1 2 3 4\n");
    ASSERT_EQ(quad.triangle_count(), 2u);
    EXPECT_NEAR(total_area(quad), 1.0, 1e-6);

    // a convex hexagon (regular, radius 1): 4 triangles covering its area 3√3/2
    std::string hex;
    for (int k = 0; k < 6; ++k) {
        const double a = k * M_PI / 3;
        hex += "v " + std::to_string(std::cos(a)) + " " + std::to_string(std::sin(a)) + " 0\n";
    }
    const MeshData h = parse_test_obj(hex + "f 1 2 3 4 5 6\n");
    ASSERT_EQ(h.triangle_count(), 4u);
    EXPECT_NEAR(total_area(h), 3 * std::sqrt(3.0) / 2, 1e-4);
    for (size_t t = 0; t < h.triangle_count(); ++t) EXPECT_GT(obj_triangle_area(h, t), 0.1);

    // a concave L-shaped hexagon of area 3
    const MeshData l =
        parse_test_obj("v 0 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\nf 1 2 3 4 5 6\n");
    ASSERT_EQ(l.triangle_count(), 4u);
    EXPECT_NEAR(total_area(l), 3.0, 1e-5);
}

TEST(ObjLoader, LargeFacesAcrossGroupsAndMaterialsKeepTheirOrder) {
    // a 300-gon (tinyobjloader counts corners in a byte), a concave hexagon, a quad and a
    // triangle, with groups, objects and materials changing between them
    std::string obj = "mtllib x.mtl\n";
    for (int k = 0; k < 300; ++k) {
        const double a = 2 * M_PI * k / 300;
        obj += "v " + std::to_string(std::cos(a)) + " " + std::to_string(std::sin(a)) + " 0\n";
    }
    obj += "v 0 0 1\nv 2 0 1\nv 2 1 1\nv 1 1 1\nv 1 2 1\nv 0 2 1\n";  // 301–306: an L
    obj += "g big\nusemtl red\nf";
    for (int k = 1; k <= 300; ++k) obj += " " + std::to_string(k);
    obj += "\ng ell\nusemtl blue\nf 301 302 303 304 305 306\no other\nf 301 302 303 306\n";
    obj += "usemtl red\nf 301 302 306\n";
    Files files;
    files.text["m/x.mtl"] = "newmtl red\nKd 1 0 0\nnewmtl blue\nKd 0 0 1\n";
    const MeshData m = parse_test_obj(obj, nullptr, files);
    // the 300-gon: up to 298 triangles (in float, corners in line are dropped) of material 0
    double big = 0, ell = 0, rest = 0;
    size_t t = 0;
    for (; t < m.triangle_count() && m.material[t] == 0; ++t) big += obj_triangle_area(m, t);
    EXPECT_NEAR(big, 150 * std::sin(2 * M_PI / 300), 1e-4);
    for (size_t k = 0; k < 4; ++k, ++t) {
        ASSERT_LT(t, m.triangle_count());
        EXPECT_EQ(m.material[t], 1);
        ell += obj_triangle_area(m, t);
    }
    EXPECT_NEAR(ell, 3.0, 1e-5);
    for (size_t k = 0; k < 2; ++k, ++t) {
        EXPECT_EQ(m.material[t], 1);  // a new object keeps the material
        rest += obj_triangle_area(m, t);
    }
    EXPECT_NEAR(rest, 3.0, 1e-5);  // (0,0) (2,0) (2,1) (0,2)
    ASSERT_EQ(t + 1, m.triangle_count());
    EXPECT_EQ(m.material[t], 0);
    EXPECT_EQ(m.position[3 * t], 300u);
}

TEST(ObjLoader, NegativeIndicesAreRelative) {
    const MeshData a = parse_test_obj(std::string(kSquare) + "f -4 -3 -2\nv 5 5 5\nf -1 -5 -4\n");
    EXPECT_EQ(a.position, (std::vector<uint32_t>{0, 1, 2, 4, 0, 1}));
}

TEST(ObjLoader, VertexReferenceFormsMix) {
    const MeshData m = parse_test_obj(
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvn 0 0 1\nvn 0 0.5 0.5\n"
        "f 1/1/1 2//2 3/2\n");
    EXPECT_EQ(m.position, (std::vector<uint32_t>{0, 1, 2}));
    EXPECT_EQ(m.normal, (std::vector<int32_t>{0, 1, -1}));
    ASSERT_EQ(m.normals.size(), 2u);
    EXPECT_EQ(m.normals[1], (Vec3{0, 0.5f, 0.5f}));  // as given; normalised later
}

TEST(ObjLoader, CrlfLineEndsReadLikeLf) {
    const std::string lf = std::string(kSquare) + "vn 0 0 1\nf 1//1 2//1 3//1 4//1\n";
    std::string crlf;
    for (char c : lf) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
    const MeshData a = parse_test_obj(lf), b = parse_test_obj(crlf);
    EXPECT_EQ(a.positions, b.positions);
    EXPECT_EQ(a.position, b.position);
    EXPECT_EQ(a.normal, b.normal);
    // line numbers count CRLF once
    EXPECT_EQ(obj_error_of("v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 9\r\n"),
              "m/x.obj:4: f: vertex index 9 in \"9\" out of range: 3 vertices defined before "
              "this line");
    // a byte order mark is skipped
    EXPECT_EQ(parse_test_obj("\xEF\xBB\xBF" + lf).position, a.position);
}

TEST(ObjLoader, AFileWithoutFacesIsEmptyWithAWarning) {
    std::vector<std::string> w;
    const MeshData m = parse_test_obj("# nothing\nv 0 0 0\nv 1 0 0\n", &w);
    EXPECT_EQ(m.triangle_count(), 0u);
    ASSERT_EQ(w.size(), 1u);
    EXPECT_EQ(w[0], "m/x.obj: no faces; the mesh is empty");
    EXPECT_EQ(parse_test_obj("").triangle_count(), 0u);
}

TEST(ObjLoader, OtherStatementsAreIgnored) {
    const MeshData m =
        parse_test_obj(std::string(kSquare) +
                       "o thing\ng group\ns 1\nvp 0.5\nl 1 2\np 3\ncurv 0 1 1 2\nf 1 2 3\ns off\n");
    EXPECT_EQ(m.triangle_count(), 1u);
}

TEST(ObjLoader, BadInputNamesFileAndLine) {
    const std::string v3 = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    EXPECT_EQ(obj_error_of(v3 + "f 1 2 4\n"),
              "m/x.obj:4: f: vertex index 4 in \"4\" out of range: 3 vertices defined before "
              "this line");
    EXPECT_EQ(obj_error_of(v3 + "f 1 2 -4\n"),
              "m/x.obj:4: f: vertex index -4 in \"-4\" out of range: 3 vertices defined before "
              "this line");
    EXPECT_EQ(obj_error_of(v3 + "f 1 2 0\n"),
              "m/x.obj:4: f: index 0 in \"0\" (OBJ indices start at 1)");
    EXPECT_EQ(obj_error_of(v3 + "f 1//1 2//1 3//1\n"),
              "m/x.obj:4: f: normal index 1 in \"1//1\" out of range: 0 normals defined before "
              "this line");
    EXPECT_EQ(obj_error_of(v3 + "vt 0 0\nf 1/2 2/1 3/1\n"),
              "m/x.obj:5: f: texture coordinate index 2 in \"1/2\" out of range: 1 texture "
              "coordinate defined before this line");
    EXPECT_EQ(obj_error_of(v3 + "f 1 2\n"), "m/x.obj:4: f: expected at least 3 vertices, got 2");
    EXPECT_EQ(obj_error_of(v3 + "f 1 2 3x\n"), "m/x.obj:4: f: malformed vertex reference \"3x\"");
    EXPECT_EQ(obj_error_of(v3 + "f 1/1/1/1 2 3\n"),
              "m/x.obj:4: f: malformed vertex reference \"1/1/1/1\" (expected v, v/vt, v/vt/vn "
              "or v//vn)");
    EXPECT_EQ(obj_error_of("v 0 0 0\nv 1 0 0\nv 0 1.2.5 0\n"),
              "m/x.obj:3: v: malformed number \"1.2.5\"");
    EXPECT_EQ(obj_error_of("v 0 0 zero\n"), "m/x.obj:1: v: malformed number \"zero\"");
    EXPECT_EQ(obj_error_of("v 0 0\n"), "m/x.obj:1: v: expected at least 3 numbers, got 2");
    EXPECT_EQ(obj_error_of("v 0 nan 0\n"), "m/x.obj:1: v: not a finite number \"nan\"");
    EXPECT_EQ(obj_error_of("v 0 0 -inf\n"), "m/x.obj:1: v: not a finite number \"-inf\"");
    EXPECT_EQ(obj_error_of("v 0 0 1e39\n"), "m/x.obj:1: v: number out of float range \"1e39\"");
    EXPECT_EQ(obj_error_of("v 0 0 1e999\n"), "m/x.obj:1: v: number out of range \"1e999\"");
    EXPECT_EQ(obj_error_of("vn 0 1\n"), "m/x.obj:1: vn: expected 3 numbers, got 2");
    // what passes: signs, exponents, leading dots, tiny numbers
    const MeshData ok = parse_test_obj("v +1 -2.5e1 .5\nv 1e-50 0 0\nv 0 1 0\nf 1 2 3\n");
    EXPECT_EQ(ok.positions[0], (Vec3{1, -25, 0.5f}));
}

TEST(ObjLoader, MissingFileIsAnInputError) {
    std::vector<std::string> w;
    try {
        load_obj("/nonexistent/dir/x.obj", true, w);
        FAIL();
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()),
                  "/nonexistent/dir/x.obj: cannot read: No such file or directory");
    }
}

// ---- MTL ----------------------------------------------------------------------------------

const char* kTwoFaces =
    "mtllib x.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl gold\nf 1 2 3\nusemtl glass\nf 1 3 2\n"
    "usemtl\nf 2 3 1\n";

TEST(ObjLoader, MtlMaterialsAreMapped) {
    Files files;
    files.text["m/x.mtl"] =
        "# gold and glass\n"
        "newmtl gold\nKa 0.2 0.1 0.05\nKd 0.8 0.6 0.2\nKs 0.9 0.8 0.4\nNs 250\nillum 3\n"
        "newmtl glass\nKd 0.5\nNi 1.5\nd 0.25\nillum 7\n"
        "newmtl unused\nKd 1 0 0\n";
    std::vector<std::string> w;
    const MeshData m = parse_test_obj(kTwoFaces, &w, files);
    EXPECT_TRUE(w.empty()) << w[0];
    ASSERT_EQ(m.materials.size(), 2u);  // those faces use, in order of use
    EXPECT_EQ(m.material, (std::vector<int32_t>{0, 1, -1}));

    const Material& gold = m.materials[0];
    EXPECT_EQ(gold.name, "x.obj:gold");
    EXPECT_EQ(gold.ka, (Rgb{0.2f, 0.1f, 0.05f}));
    EXPECT_EQ(gold.kd, (Rgb{0.8f, 0.6f, 0.2f}));
    EXPECT_EQ(gold.ks, (Rgb{0.9f, 0.8f, 0.4f}));
    EXPECT_EQ(gold.n, 250.0f);
    EXPECT_FLOAT_EQ(gold.reflection, (0.9f + 0.8f + 0.4f) / 3);  // illum 3: mean of Ks
    EXPECT_EQ(gold.transparency, 0.0f);
    EXPECT_EQ(gold.ior, 1.0f);

    const Material& glass = m.materials[1];
    EXPECT_EQ(glass.name, "x.obj:glass");
    EXPECT_EQ(glass.kd, Rgb(0.5f));  // one value: all channels
    const Material def;              // keys not given keep the default material's
    EXPECT_EQ(glass.ka, def.ka);
    EXPECT_EQ(glass.ks, def.ks);
    EXPECT_EQ(glass.n, def.n);
    EXPECT_EQ(glass.ior, 1.5f);
    EXPECT_EQ(glass.transparency, 0.75f);                                     // 1 − d
    EXPECT_FLOAT_EQ(glass.reflection, (def.ks.x + def.ks.y + def.ks.z) / 3);  // illum 7
}

TEST(ObjLoader, MtlEdgeValues) {
    Files files;
    files.text["m/x.mtl"] =
        "newmtl gold\nNs 0\nNi 0.5\nTr 0.3\nillum 2\nKs 1.5 0.5 -0.1\n"
        "newmtl glass\nd 0.4\nTr 0.9\n";
    std::vector<std::string> w;
    const MeshData m = parse_test_obj(kTwoFaces, &w, files);
    ASSERT_EQ(m.materials.size(), 2u);
    EXPECT_EQ(m.materials[0].n, 1.0f);                      // Ns ≤ 0 → 1 (n > 0)
    EXPECT_EQ(m.materials[0].ior, 1.0f);                    // Ni < 1 → 1
    EXPECT_FLOAT_EQ(m.materials[0].transparency, 0.3f);     // Tr
    EXPECT_EQ(m.materials[0].reflection, 0.0f);             // illum 2: no reflection
    EXPECT_EQ(m.materials[0].ks, (Rgb{1.0f, 0.5f, 0.0f}));  // clamped, with warnings
    EXPECT_FLOAT_EQ(m.materials[1].transparency, 0.6f);     // d wins over a later Tr
    ASSERT_EQ(w.size(), 2u);
    EXPECT_EQ(w[0], "m/x.mtl:6: Ks 1.5 is outside [0, 1]; 1 is used");
    EXPECT_EQ(w[1], "m/x.mtl:6: Ks -0.1 is outside [0, 1]; 0 is used");
}

TEST(ObjLoader, MissingMtlWarnsAndUsesTheDefault) {
    std::vector<std::string> w;
    const MeshData m = parse_test_obj(kTwoFaces, &w);
    EXPECT_EQ(m.triangle_count(), 3u);
    EXPECT_TRUE(m.materials.empty());
    EXPECT_EQ(m.material, (std::vector<int32_t>{-1, -1, -1}));
    ASSERT_EQ(w.size(), 1u);  // one warning, not one per usemtl
    EXPECT_EQ(w[0],
              "m/x.obj:1: cannot read MTL file m/x.mtl: No such file or directory; using the "
              "default material");
}

TEST(ObjLoader, UnknownUsemtlWarns) {
    Files files;
    files.text["m/x.mtl"] = "newmtl gold\nKd 1 1 0\n";
    std::vector<std::string> w;
    const MeshData m = parse_test_obj(kTwoFaces, &w, files);
    EXPECT_EQ(m.material, (std::vector<int32_t>{0, -1, -1}));
    ASSERT_EQ(w.size(), 1u);
    EXPECT_EQ(w[0],
              "m/x.obj:7: usemtl glass: no such material in the MTL files; its faces use the "
              "default material");
}

TEST(ObjLoader, LongNamesAreShortenedInWarnings) {
    const std::string name(10485760, 'n');
    Files files;
    files.text["m/x.mtl"] = "newmtl gold\nKd 1 1 0\n";
    std::vector<std::string> w;
    parse_test_obj("mtllib x.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl " + name + "\nf 1 2 3\n", &w,
                   files);
    ASSERT_EQ(w.size(), 1u);
    EXPECT_EQ(w[0], "m/x.obj:5: usemtl " + std::string(40, 'n') +
                        "\xE2\x80\xA6 (10485760 characters): no such material in the MTL files; "
                        "its faces use the default material");
    parse_test_obj("mtllib " + name + "\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", &w, files);
    ASSERT_EQ(w.size(), 1u);
    EXPECT_LT(w[0].size(), 400u);
    EXPECT_THAT(w[0], HasSubstr("characters): No such file or directory"));
}

TEST(ObjLoader, MaterialsAreNotReadWhenTheObjectNamesOne) {
    std::vector<std::string> w;
    const MeshData m = parse_test_obj(kTwoFaces, &w, {}, /*with_materials=*/false);
    EXPECT_TRUE(w.empty());
    EXPECT_EQ(m.material, (std::vector<int32_t>{-1, -1, -1}));
}

TEST(ObjLoader, BadMtlNamesTheMtlFileAndLine) {
    Files files;
    files.text["m/x.mtl"] = "newmtl gold\nKd 1 1 0\nNs 1O0\n";
    EXPECT_EQ(obj_error_of(kTwoFaces, files), "m/x.mtl:3: Ns: malformed number \"1O0\"");
    files.text["m/x.mtl"] = "newmtl gold\nKd 1 1\n";
    EXPECT_EQ(obj_error_of(kTwoFaces, files), "m/x.mtl:2: Kd: expected 1 or 3 numbers, got 2");
    files.text["m/x.mtl"] = "newmtl gold\nillum three\n";
    EXPECT_EQ(obj_error_of(kTwoFaces, files),
              "m/x.mtl:2: illum: expected an integer, got \"illum three\"");
}

// ---- through the scene loader -------------------------------------------------------------

TEST(ObjLoader, SceneMaterialsComeFromTheMtlUnlessTheObjectNamesOne) {
    const auto dir = std::filesystem::temp_directory_path() / "luz_obj_test";
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "x.obj") << kTwoFaces;
    std::ofstream(dir / "x.mtl") << "newmtl gold\nKd 1 0.8 0\nnewmtl glass\nd 0.1\n";
    std::ofstream(dir / "s.json") << R"({"objects": [
        {"type": "mesh", "file": "x.obj"},
        {"type": "mesh", "file": "x.obj", "material": "vidro"},
        {"type": "mesh", "file": "x.obj", "smooth": false}]})";
    const SceneDesc s = load_scene((dir / "s.json").string());
    EXPECT_TRUE(s.warnings.empty());
    ASSERT_EQ(s.objects.size(), 3u);
    // object 0: MTL materials added to the scene once, named file:material
    const std::vector<int>& map0 = s.objects[0].mesh_materials;
    ASSERT_EQ(map0.size(), 2u);
    EXPECT_EQ(s.materials[map0[0]].name, "x.obj:gold");
    EXPECT_EQ(s.materials[map0[0]].kd, (Rgb{1, 0.8f, 0}));
    EXPECT_EQ(s.materials[map0[1]].name, "x.obj:glass");
    EXPECT_FLOAT_EQ(s.materials[map0[1]].transparency, 0.9f);
    EXPECT_EQ(s.objects[0].material, 0);  // faces without a material: the default
    // object 1 names a material: no MTL mapping
    EXPECT_TRUE(s.objects[1].mesh_materials.empty());
    EXPECT_EQ(s.materials[s.objects[1].material].name, "vidro");
    // object 2 shares object 0's file and materials
    EXPECT_EQ(s.objects[2].mesh, s.objects[0].mesh);
    EXPECT_EQ(s.objects[2].mesh_materials, map0);

    // a missing MTL: a warning, the render goes on
    std::filesystem::remove(dir / "x.mtl");
    const SceneDesc w = load_scene((dir / "s.json").string());
    ASSERT_EQ(w.warnings.size(), 1u);
    EXPECT_THAT(w.warnings[0], HasSubstr("x.obj:1: cannot read MTL file"));
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace luz
