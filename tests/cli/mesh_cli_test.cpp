// `luz render` with meshes: a missing MTL file is a warning (exit 0), demo:bunny finds its
// OBJ from any folder, and --stats reports the BVH and the intersection time share with both
// accelerations, which give the same image.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "cli/run_luz.h"

namespace luz::test {
namespace {

class MeshCli : public TempDirTest {};

TEST_F(MeshCli, MissingMtlWarnsAndRenders) {
    write_file(dir_ / "x.obj",
               "mtllib gone.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl gold\nf 1 2 3\n");
    write_file(dir_ / "s.json", R"({"objects": [{"type": "mesh", "file": "x.obj"}]})");
    const RunResult r = run_luz({"render", "s.json", "-o", "out.png", "--width", "32", "--height",
                                 "24", "--pipeline", "raytrace"},
                                dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err,
              "luz: warning: x.obj:1: cannot read MTL file gone.mtl: No such file or directory; "
              "using the default material\n");
    EXPECT_TRUE(std::filesystem::exists(dir_ / "out.png"));
}

TEST_F(MeshCli, BunnyFromAnyFolderWithBvhStatsAndTheSameImageWithoutIt) {
    const std::vector<std::string> common = {"render",   "demo:bunny", "--width",   "80",
                                             "--height", "60",         "--threads", "2"};
    std::vector<std::string> a = common, b = common;
    a.insert(a.end(), {"-o", "bvh.png", "--stats", "bvh.json"});
    b.insert(b.end(), {"-o", "none.png", "--stats", "none.json", "--set", "render.accel=none"});
    const RunResult ra = run_luz(a, dir_), rb = run_luz(b, dir_);
    ASSERT_EQ(ra.status, 0) << ra.err;
    ASSERT_EQ(rb.status, 0) << rb.err;
    EXPECT_EQ(ra.err, "");
    EXPECT_EQ(read_file(dir_ / "bvh.png"), read_file(dir_ / "none.png"));

    const nlohmann::json sb = nlohmann::json::parse(read_file(dir_ / "bvh.json"));
    const nlohmann::json sn = nlohmann::json::parse(read_file(dir_ / "none.json"));
    EXPECT_EQ(sb["accel"], "bvh");
    EXPECT_EQ(sn["accel"], "none");
    EXPECT_EQ(sb["triangles"], 3674) << "raytrace: triangles in meshes";
    EXPECT_GT(sb["bvh_nodes"].get<uint64_t>(), 200u);  // 8-wide nodes (Bvh8): 423 here
    EXPECT_EQ(sn["bvh_nodes"], 0);
    EXPECT_GT(sb["bvh_build_seconds"].get<double>(), 0.0);
    EXPECT_GT(sb["bvh_bytes"].get<uint64_t>(), sb["bvh_nodes"].get<uint64_t>() * 32);
    const double share = sb["intersection_time"]["share"].get<double>();
    EXPECT_GT(share, 0.0);
    EXPECT_LE(share, 1.0);
    EXPECT_TRUE(sb["intersection_time"]["method"].is_string());
    EXPECT_EQ(sb["rays"], sn["rays"]);
    EXPECT_LT(sb["intersection_tests"]["primitive"].get<uint64_t>() * 20,
              sn["intersection_tests"]["primitive"].get<uint64_t>());
}

TEST_F(MeshCli, ZbufferHasNoIntersectionTime) {
    const RunResult r = run_luz({"render", "demo:bunny", "--width", "40", "--height", "30",
                                 "--pipeline", "zbuffer", "-o", "z.png", "--stats", "z.json"},
                                dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    const nlohmann::json s = nlohmann::json::parse(read_file(dir_ / "z.json"));
    EXPECT_TRUE(s["intersection_time"]["share"].is_null());
    EXPECT_EQ(s["bvh_nodes"], 0);
    EXPECT_GT(s["triangles"].get<uint64_t>(), 1000u);  // the bunny's front, rasterized
}

}  // namespace
}  // namespace luz::test
