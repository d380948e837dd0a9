// Bad input (docs/CLI.md): exit status 2, one line on standard error naming the file or option and
// the place (key path or line:column), and no output file left behind.
#include <gtest/gtest.h>

#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "cli/run_luz.h"

namespace luz::test {
namespace {

struct BadCase {
    std::string name;
    std::map<std::string, std::string> files;  ///< written into the test's folder first
    std::vector<std::string> args;             ///< after "luz"
    std::vector<std::string> fragments;        ///< each must appear in the error line
};

/// gtest prints a failing parameter with this (instead of its bytes).
void PrintTo(const BadCase& c, std::ostream* os) { *os << c.name; }

/// A scene file "s.json" holding `json`, rendered with `extra` options to out.png.
BadCase scene_case(std::string name, std::string json, std::vector<std::string> fragments,
                   std::vector<std::string> extra = {}) {
    BadCase c{std::move(name),
              {{"s.json", std::move(json)}},
              {"render", "s.json", "-o", "out.png"},
              std::move(fragments)};
    c.args.insert(c.args.end(), extra.begin(), extra.end());
    return c;
}

/// demo:primitives rendered with `extra` options to out.png.
BadCase option_case(std::string name, std::vector<std::string> extra,
                    std::vector<std::string> fragments) {
    BadCase c{
        std::move(name), {}, {"render", "demo:primitives", "-o", "out.png"}, std::move(fragments)};
    c.args.insert(c.args.end(), extra.begin(), extra.end());
    return c;
}

const std::string kSphere = R"({"type": "sphere"})";

std::vector<BadCase> bad_cases() {
    std::vector<BadCase> v;
    // --- the scene file's text
    v.push_back(scene_case("json_syntax_error",
                           "{\n  \"objects\": [\n    {\"type\": \"sphere\",,}\n  ]\n}\n",
                           {"s.json", ":3:"}));
    v.push_back(scene_case("json_truncated", "{\n  \"objects\": [\n", {"s.json", ":3:"}));
    v.push_back(scene_case("json_number_overflow",
                           R"({"objects": [{"type": "sphere", "radius": 1e999}]})",
                           {"s.json", "1e999"}));
    // --- keys and types
    v.push_back(scene_case("unknown_top_level_key", R"({"objetcs": []})", {"s.json", "objetcs"}));
    v.push_back(scene_case("unknown_object_key", R"({"objects": [{"type": "sphere", "radus": 2}]})",
                           {"s.json", "objects.0", "radus"}));
    v.push_back(scene_case("wrong_type",
                           R"({"image": {"width": "800"}, "objects": [)" + kSphere + "]}",
                           {"s.json", "image.width"}));
    v.push_back(scene_case("unknown_shape_type", R"({"objects": [{"type": "teapot"}]})",
                           {"s.json", "objects.0.type"}));
    // --- values out of range
    v.push_back(scene_case("negative_radius", R"({"objects": [{"type": "sphere", "radius": -1}]})",
                           {"s.json", "objects.0.radius"}));
    v.push_back(scene_case("zero_height", R"({"objects": [{"type": "cylinder", "height": 0}]})",
                           {"s.json", "objects.0.height"}));
    v.push_back(scene_case("ka_above_one",
                           R"({"materials": {"red": {"ka": 1.5}},
                               "objects": [{"type": "sphere", "material": "red"}]})",
                           {"s.json", "materials.red.ka"}));
    v.push_back(scene_case("n_zero",
                           R"({"materials": {"red": {"n": 0}},
                               "objects": [{"type": "sphere", "material": "red"}]})",
                           {"s.json", "materials.red.n"}));
    v.push_back(scene_case("ior_below_one",
                           R"({"materials": {"glass": {"ior": 0.5}},
                               "objects": [{"type": "sphere", "material": "glass"}]})",
                           {"s.json", "materials.glass.ior"}));
    v.push_back(scene_case("attenuation_k_zero",
                           R"({"attenuation_k": 0, "objects": [)" + kSphere + "]}",
                           {"s.json", "attenuation_k"}));
    v.push_back(scene_case("zero_axis", R"({"objects": [{"type": "cylinder", "axis": [0, 0, 0]}]})",
                           {"s.json", "objects.0.axis"}));
    v.push_back(scene_case("zero_normal",
                           R"({"objects": [{"type": "plane", "normal": [0, 0, 0]}]})",
                           {"s.json", "objects.0.normal"}));
    v.push_back(scene_case("torus_minor_not_below_major",
                           R"({"objects": [{"type": "torus", "major_radius": 1,
                                            "minor_radius": 2}]})",
                           {"s.json", "objects.0"}));
    v.push_back(scene_case("zero_scale",
                           R"({"objects": [{"type": "sphere", "transform": {"scale": 0}}]})",
                           {"s.json", "objects.0.transform.scale"}));
    v.push_back(scene_case("negative_light_intensity",
                           R"({"lights": [{"position": [0, 5, 5], "intensity": -1}],
                               "objects": [)" +
                               kSphere + "]}",
                           {"s.json", "lights.0.intensity"}));
    v.push_back(scene_case("up_parallel_to_view",
                           R"({"camera": {"position": [0, 5, 0], "look_at": [0, 0, 0],
                                          "up": [0, 1, 0]}, "objects": [)" +
                               kSphere + "]}",
                           {"s.json", "camera.up"}));
    v.push_back(scene_case("width_zero", R"({"image": {"width": 0}, "objects": [)" + kSphere + "]}",
                           {"s.json", "image.width"}));
    v.push_back(scene_case(
        "image_too_large",
        R"({"image": {"width": 100000, "height": 100000}, "objects": [)" + kSphere + "]}",
        {"s.json", "image.width"}));
    v.push_back(
        scene_case("image_too_large_for_memory",
                   R"({"image": {"width": 16384, "height": 16384}, "objects": [)" + kSphere + "]}",
                   {"s.json", "image.width", "16384x16384 needs 8.8 GiB", "4.0 GiB limit"},
                   {"--max-memory", "4G"}));
    v.push_back(scene_case("unknown_material_name",
                           R"({"objects": [{"type": "sphere", "material": "nosuch"}]})",
                           {"s.json", "objects.0.material"}));
    v.push_back(scene_case("unknown_preset",
                           R"({"materials": {"x": {"preset": "unobtainium"}},
                               "objects": [{"type": "sphere", "material": "x"}]})",
                           {"s.json", "materials.x.preset"}));
    // --- OBJ files (meshes): the OBJ file and its line; a missing file names the key too
    v.push_back(BadCase{"mesh_object",
                        {{"s.json", R"({"objects": [{"type": "mesh", "file": "nope.obj"}]})"}},
                        {"render", "s.json", "-o", "out.png"},
                        {"s.json", "objects.0.file", "nope.obj", "No such file"}});
    const std::string mesh_scene = R"({"objects": [{"type": "mesh", "file": "m/x.obj"}]})";
    v.push_back(
        BadCase{"obj_index_out_of_range",
                {{"s.json", mesh_scene}, {"m/x.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n"}},
                {"render", "s.json", "-o", "out.png"},
                {"m/x.obj:4:", "out of range"}});
    v.push_back(BadCase{
        "obj_malformed_number",
        {{"s.json", mesh_scene}, {"m/x.obj", "v 0 0 0\r\nv 1 0,5 0\r\nv 0 1 0\r\nf 1 2 3\r\n"}},
        {"render", "s.json", "-o", "out.png"},
        {"m/x.obj:2:", "malformed number \"0,5\""}});
    v.push_back(BadCase{"obj_not_finite",
                        {{"s.json", mesh_scene}, {"m/x.obj", "v 0 0 0\nv 1 0 0\nv 0 nan 0\n"}},
                        {"render", "s.json", "-o", "out.png"},
                        {"m/x.obj:3:", "not a finite number"}});
    v.push_back(BadCase{"mtl_malformed_number",
                        {{"s.json", mesh_scene},
                         {"m/x.obj", "mtllib x.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"},
                         {"m/x.mtl", "newmtl a\nKd 1 1 x\n"}},
                        {"render", "s.json", "-o", "out.png"},
                        {"m/x.mtl:2:", "malformed number"}});
    // --- the scene argument
    v.push_back(BadCase{
        "missing_scene_file", {}, {"render", "missing.json", "-o", "out.png"}, {"missing.json"}});
    v.push_back(BadCase{
        "scene_is_a_folder", {{"adir/keep", ""}}, {"render", "adir", "-o", "out.png"}, {"adir"}});
    v.push_back(
        BadCase{"unknown_demo", {}, {"render", "demo:nope", "-o", "out.png"}, {"demo:nope"}});
    // --- --set
    v.push_back(option_case("set_without_equals", {"--set", "image.width"}, {"--set"}));
    v.push_back(option_case("set_empty_path", {"--set", "=5"}, {"--set"}));
    v.push_back(option_case("set_bad_json", {"--set", "image.width=[1,"}, {"--set"}));
    v.push_back(option_case("set_unknown_key", {"--set", "image.widht=5"}, {"--set", "widht"}));
    v.push_back(
        option_case("set_wrong_type", {"--set", "image.width=\"abc\""}, {"--set", "image.width"}));
    v.push_back(
        option_case("set_bad_index", {"--set", "objects.99.radius=2"}, {"--set", "objects.99"}));
    v.push_back(option_case("set_out_of_range", {"--set", "ambient=-1"}, {"--set", "ambient"}));
    v.push_back(option_case("set_unknown_attenuation", {"--set", "attenuation=quadratic"},
                            {"--set", "attenuation", "unknown value \"quadratic\""}));
    // --- options
    v.push_back(option_case("unknown_pipeline", {"--pipeline", "foo"}, {"--pipeline"}));
    v.push_back(option_case("unknown_model", {"--model", "blinn"}, {"--model"}));
    v.push_back(option_case("unknown_aa", {"--aa", "msaa"}, {"--aa"}));
    v.push_back(
        option_case("samples_not_square", {"--aa", "grid", "--samples", "5"}, {"--samples"}));
    v.push_back(option_case("width_negative", {"--width", "-5"}, {"--width"}));
    v.push_back(option_case("width_not_a_number", {"--width", "abc"}, {"--width"}));
    v.push_back(option_case("height_zero", {"--height", "0"}, {"--height"}));
    v.push_back(option_case("max_depth_negative", {"--max-depth", "-1"}, {"--max-depth"}));
    v.push_back(option_case("threshold_negative", {"--threshold", "-0.5"}, {"--threshold"}));
    v.push_back(option_case("threads_negative", {"--threads", "-1"}, {"--threads"}));
    v.push_back(option_case("option_without_value", {"--width"}, {"--width"}));
    v.push_back(option_case("unknown_option", {"--frobnicate"}, {"--frobnicate"}));
    v.push_back(option_case("max_memory_negative", {"--max-memory", "-1"},
                            {"--max-memory", "must not be negative, got -1"}));
    v.push_back(option_case("over_memory_limit", {"--max-memory", "1M"},
                            {"demo:primitives", "image.width", "800x600 needs"}));
    v.push_back(BadCase{"bad_output_extension",
                        {},
                        {"render", "demo:primitives", "-o", "out.bmp"},
                        {"out.bmp", ".bmp"}});
    v.push_back(BadCase{
        "output_without_extension", {}, {"render", "demo:primitives", "-o", "out"}, {"out"}});
    v.push_back(BadCase{"output_folder_missing",
                        {},
                        {"render", "demo:primitives", "-o", "nodir/out.png"},
                        {"nodir"}});
    v.push_back(BadCase{"stats_folder_missing",
                        {},
                        {"render", "demo:primitives", "-o", "out.png", "--stats", "nodir/s.json"},
                        {"nodir"}});
    // --- the command itself
    v.push_back(BadCase{"no_scene_argument", {}, {"render"}, {"SCENE"}});
    v.push_back(BadCase{"no_subcommand", {}, {}, {"subcommand"}});
    v.push_back(BadCase{"unknown_subcommand", {}, {"rendr", "demo:primitives"}, {"rendr"}});
    return v;
}

class BadInput : public TempDirTest, public testing::WithParamInterface<BadCase> {};

TEST_P(BadInput, ExitsTwoWithOneLineNamingThePlaceAndLeavesNoFile) {
    const BadCase& c = GetParam();
    for (const auto& [name, content] : c.files) {
        std::filesystem::create_directories((dir_ / name).parent_path());
        write_file(dir_ / name, content);
    }
    const std::set<std::string> before = list_dir(dir_);

    const RunResult r = run_luz(c.args, dir_);
    EXPECT_EQ(r.status, 2) << "stderr: " << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << "stderr: " << r.err;
    EXPECT_FALSE(r.err.empty() || r.err.back() != '\n') << "stderr: " << r.err;
    EXPECT_EQ(r.err.find("std::"), std::string::npos) << r.err;
    for (const std::string& f : c.fragments) {
        EXPECT_NE(r.err.find(f), std::string::npos) << "missing \"" << f << "\" in: " << r.err;
    }
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(list_dir(dir_), before) << "a file was left behind";
}

INSTANTIATE_TEST_SUITE_P(Table, BadInput, testing::ValuesIn(bad_cases()),
                         [](const testing::TestParamInfo<BadCase>& info) {
                             return info.param.name;
                         });

TEST(BadInputTable, HasAtLeastThirtyCases) { EXPECT_GE(bad_cases().size(), 30u); }

class LongInput : public TempDirTest {};

TEST_F(LongInput, AValueOfTenMegabytesIsShortenedInTheMessage) {
    write_file(dir_ / "s.json", R"({"objects": [{"type": "sphere", "material": ")" +
                                    std::string(10485760, 'a') + "\"}]}");
    const RunResult r = run_luz({"render", "s.json", "-o", "out.png"}, dir_);
    EXPECT_EQ(r.status, 2) << r.err.substr(0, 300);
    EXPECT_EQ(count_lines(r.err), 1);
    EXPECT_NE(r.err.find("s.json: objects.0.material: unknown material \"aaaa"), std::string::npos)
        << r.err.substr(0, 300);
    EXPECT_NE(r.err.find("\" (10485760 characters)"), std::string::npos) << r.err.substr(0, 300);
    EXPECT_LT(r.err.size(), 1000u);
}

class ExistingOutput : public TempDirTest {};

TEST_F(ExistingOutput, IsLeftByteIdenticalAfterAFailingRender) {
    const std::string precious = "not really a png, but precious\n";
    write_file(dir_ / "out.png", precious);
    write_file(dir_ / "s.json", R"({"objects": [{"type": "sphere", "radius": -1}]})");
    const std::set<std::string> before = list_dir(dir_);

    const RunResult r = run_luz({"render", "s.json", "-o", "out.png"}, dir_);

    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_EQ(read_file(dir_ / "out.png"), precious);
    EXPECT_EQ(list_dir(dir_), before);
}

TEST_F(ExistingOutput, IsLeftByteIdenticalWhenTheOptionsAreBad) {
    const std::string precious = "precious\n";
    write_file(dir_ / "out.png", precious);

    const RunResult r =
        run_luz({"render", "demo:primitives", "-o", "out.png", "--pipeline", "nope"}, dir_);

    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_EQ(read_file(dir_ / "out.png"), precious);
}

}  // namespace
}  // namespace luz::test

namespace luz::test {
namespace {

// Failures that are not bad input (here: a place where no file can be made) exit with 1,
// one line "luz: ..." and leave nothing behind.
class OtherFailure : public TempDirTest {};

TEST_F(OtherFailure, UnwritableOutputExitsOne) {
    const RunResult r = run_luz(
        {"render", "demo:primitives", "--width", "8", "--height", "8", "-o", "/proc/luz-x.png"},
        dir_);
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_EQ(r.err.rfind("luz: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find("/proc/luz-x.png"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("std::"), std::string::npos) << r.err;
    EXPECT_EQ(r.out, "");
}

TEST_F(OtherFailure, UnwritableStatsLeavesNoImage) {
    const RunResult r = run_luz({"render", "demo:primitives", "--width", "8", "--height", "8", "-o",
                                 "x.png", "--stats", "/proc/luz-s.json"},
                                dir_);
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("/proc/luz-s.json"), std::string::npos) << r.err;
    EXPECT_TRUE(list_dir(dir_).empty()) << "the image was left behind";
}

}  // namespace
}  // namespace luz::test
