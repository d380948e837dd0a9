// `mpirun -np 3 luz render --frames` (docs/DISTRIBUTED.md): every frame the same bytes as in one
// process, and --stats with `processes` and `primary_rays_by_process` (adding up to rays.primary)
// for the totals and each frame, and for a single frame.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mpi/mpi_run.h"

namespace luz::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

void expect_shared(const json& s, int np, const std::string& what) {
    EXPECT_EQ(s["processes"], np) << what;
    ASSERT_TRUE(s["primary_rays_by_process"].is_array()) << what;
    ASSERT_EQ(s["primary_rays_by_process"].size(), static_cast<size_t>(np)) << what;
    uint64_t sum = 0;
    for (const json& n : s["primary_rays_by_process"]) sum += n.get<uint64_t>();
    EXPECT_GT(sum, 0u) << what;
    EXPECT_EQ(sum, s["rays"]["primary"].get<uint64_t>()) << what;
}

class FramesMpi : public MpiTest {};

TEST_F(FramesMpi, EveryFrameIsTheOneProcessFrame) {
    // Adaptive: two passes a frame, so the message tags of one frame follow the last's.
    const std::vector<std::string> args = {
        "render", "demo:highlight", "--width",   "64",    "--height",
        "48",     "--frames",       "2:6",       "--aa",  "adaptive",
        "--aov",  "depth,specular", "--aa-mask", "m.png", "-o",
        "x.pfm",  "--stats",        "s.json",    "-q"};
    const fs::path one = dir_ / "one", many = dir_ / "many";
    fs::create_directory(one);
    fs::create_directory(many);
    const RunResult r1 = run_luz(args, one);
    ASSERT_EQ(r1.status, 0) << r1.err;
    const RunResult r = run_mpirun(3, args, many);
    ASSERT_EQ(r.status, 0) << r.err;

    std::set<std::string> expected = {"s.json"};
    for (int f = 2; f < 6; ++f) {
        const std::string n = "000" + std::to_string(f);
        for (const std::string& name : {"x." + n + ".pfm", "x." + n + ".depth.pfm",
                                        "x." + n + ".specular.pfm", "m." + n + ".png"}) {
            expected.insert(name);
            const std::string a = read_file(one / name), b = read_file(many / name);
            EXPECT_FALSE(a.empty()) << name;
            EXPECT_TRUE(a == b) << name << " differs";
        }
    }
    EXPECT_EQ(list_dir(one), expected);
    EXPECT_EQ(list_dir(many), expected);
    // The frames differ (the highlight sweeps): a mix-up of frames would show.
    EXPECT_NE(read_file(many / "x.0002.pfm"), read_file(many / "x.0005.pfm"));

    const json s1 = json::parse(read_file(one / "s.json"));
    const json s = json::parse(read_file(many / "s.json"));
    expect_shared(s, 3, "totals");
    EXPECT_EQ(s["rays"], s1["rays"]);
    EXPECT_EQ(s["frame_range"], json::array({2, 6}));
    ASSERT_TRUE(s["frames"].is_array());
    ASSERT_EQ(s["frames"].size(), 4u);
    for (int i = 0; i < 4; ++i) {
        const json& f = s["frames"][i];
        EXPECT_EQ(f["frame"], 2 + i);
        expect_shared(f, 3, "frame " + std::to_string(2 + i));
        EXPECT_EQ(f["rays"], s1["frames"][i]["rays"]) << "frame " << 2 + i;
    }
}

TEST_F(FramesMpi, SingleFrameStatsSayHowTheWorkWasShared) {
    const RunResult r = run_mpirun(3,
                                   {"render", "demo:whitted", "--width", "97", "--height", "71",
                                    "--aa", "adaptive", "-o", "x.png", "--stats", "s.json", "-q"},
                                   dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    const json s = json::parse(read_file(dir_ / "s.json"));
    expect_shared(s, 3, "one frame");
    EXPECT_FALSE(s.contains("frames"));
    EXPECT_EQ(list_dir(dir_), (std::set<std::string>{"x.png", "s.json"}));
}

}  // namespace
}  // namespace luz::test
