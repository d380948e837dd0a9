// `luz render` on NFF scenes (docs/SCENES.md#nff): the file's resolution unless --width/--height,
// --set on its materials f1…, --region and --aov as on any scene, and bad NFF refused with one
// FILE:LINE line and nothing written.
#include <gtest/gtest.h>

#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/run_luz.h"
#include "cli/signal_luz.h"

namespace luz::test {
namespace {

class NffCli : public TempDirTest {
  protected:
    void SetUp() override {
        TempDirTest::SetUp();
        std::filesystem::copy_file(std::string(LUZ_SOURCE_DIR) + "/tests/scenes/nff/small.nff",
                                   dir_ / "small.nff");
    }
};

/// The width and height a PNG's header gives.
std::pair<int, int> png_width_height(const std::string& png) {
    const auto be = [&](size_t at) {
        return (int(uint8_t(png[at])) << 24) | (int(uint8_t(png[at + 1])) << 16) |
               (int(uint8_t(png[at + 2])) << 8) | int(uint8_t(png[at + 3]));
    };
    return {be(16), be(20)};
}

TEST_F(NffCli, RendersAtTheFilesResolutionUnlessTold) {
    const RunResult r = run_luz({"render", "small.nff", "--stats", "s.json"}, dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_EQ(png_width_height(read_file(dir_ / "small.png")), std::make_pair(48, 32));
    const auto stats = nlohmann::json::parse(read_file(dir_ / "s.json"));
    EXPECT_EQ(stats["pipeline"], "raytrace");
    EXPECT_GT(stats["rays"]["shadow"].get<int>(), 0);

    const RunResult w =
        run_luz({"render", "small.nff", "-o", "w.png", "--width", "20", "--height", "10"}, dir_);
    ASSERT_EQ(w.status, 0) << w.err;
    EXPECT_EQ(png_width_height(read_file(dir_ / "w.png")), std::make_pair(20, 10));
}

TEST_F(NffCli, SetChangesAMaterialByItsName) {
    ASSERT_EQ(run_luz({"render", "small.nff", "-o", "a.png"}, dir_).status, 0);
    const RunResult r =
        run_luz({"render", "small.nff", "-o", "b.png", "--set", "materials.f1.kd=[0,0,1]"}, dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(read_file(dir_ / "a.png"), read_file(dir_ / "b.png"));
    const RunResult bad =
        run_luz({"render", "small.nff", "-o", "c.png", "--set", "materials.f1.kd=2"}, dir_);
    EXPECT_EQ(bad.status, 2);
    EXPECT_EQ(bad.err, "--set materials.f1.kd=2: must be in [0, 1], got 2\n");
    EXPECT_FALSE(std::filesystem::exists(dir_ / "c.png"));
}

TEST_F(NffCli, RegionAndAovWorkAsOnAnyScene) {
    const RunResult r = run_luz(
        {"render", "small.nff", "-o", "r.png", "--region", "8,4,40,28", "--aov", "depth,normal"},
        dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(png_width_height(read_file(dir_ / "r.png")), std::make_pair(32, 24));
    EXPECT_TRUE(std::filesystem::exists(dir_ / "r.depth.png"));
    EXPECT_TRUE(std::filesystem::exists(dir_ / "r.normal.png"));
}

TEST_F(NffCli, BadNffIsExit2WithOneLineAndNothingWritten) {
    write_file(dir_ / "bad.nff",
               "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 1\nresolution 8 8\n"
               "s 0 0 0\n");
    const RunResult r = run_luz({"render", "bad.nff", "-o", "out.png"}, dir_);
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.err, "bad.nff:8: s: expected 4 numbers, got 3\n");
    EXPECT_EQ(list_dir(dir_), (std::set<std::string>{"bad.nff", "small.nff"}));

    write_file(dir_ / "late.nff", "s 0 0 0 1\nv\n");
    const RunResult late = run_luz({"render", "late.nff"}, dir_);
    EXPECT_EQ(late.status, 2);
    EXPECT_EQ(count_lines(late.err), 1);
    EXPECT_NE(late.err.find("late.nff:1: s: before \"v\""), std::string::npos) << late.err;
}

TEST_F(NffCli, CheckpointResumesToTheBitsOfAnUninterruptedRender) {
    const std::string gears = std::string(LUZ_SOURCE_DIR) + "/scenes/spd/gears.nff";
    const std::vector<std::string> common = {"render", gears,  "--width", "200",       "--height",
                                             "200",    "--aa", "grid",    "--samples", "4"};
    std::vector<std::string> plain = common, resumed = common;
    plain.insert(plain.end(), {"-o", "plain.png", "-q"});
    resumed.insert(resumed.end(), {"-o", "resumed.png", "--checkpoint", "g.ckpt", "-q"});
    ASSERT_EQ(run_luz(plain, dir_).status, 0);
    // Interrupted once its first periodic write (every 0.05 s here) is there (unless it
    // finished first: it takes about 0.3 s), then resumed.
    setenv("LUZ_CHECKPOINT_SECONDS", "0.05", 1);
    const Signalled s =
        signal_luz(resumed, dir_, SIGINT, [&] { return std::filesystem::exists(dir_ / "g.ckpt"); });
    unsetenv("LUZ_CHECKPOINT_SECONDS");
    EXPECT_TRUE(s.sent);
    if (s.sent && s.status != 0) {
        EXPECT_EQ(s.status, 130) << s.err;
        EXPECT_TRUE(std::filesystem::exists(dir_ / "g.ckpt"));
        EXPECT_FALSE(std::filesystem::exists(dir_ / "resumed.png"));
        const RunResult r = run_luz(resumed, dir_);
        ASSERT_EQ(r.status, 0) << r.err;
    }
    EXPECT_EQ(read_file(dir_ / "resumed.png"), read_file(dir_ / "plain.png"));
    EXPECT_FALSE(std::filesystem::exists(dir_ / "g.ckpt"));
}

TEST_F(NffCli, OnePixelHoldsTheHandComputedPhongWithoutDistanceAttenuation) {
    // The centre ray meets the unit sphere at P = (0, 0, 1), N = L = S = (0, 0, 1): cosθ = cosα
    // = 1. One light without colour: Il = 1/√1; Ia = √1/(2·1) = 0.5; Kd·rgb = (0.8, 0.4, 0.2) = Ka;
    // Ks = 0.1. attenuation none: I = Ia·Ka + Il·(Kd·cosθ + Ks·cosα^n) + 0.1·(background 0)
    // = (0.4, 0.2, 0.1) + (0.8, 0.4, 0.2) + 0.1 = (1.3, 0.7, 0.4).
    write_file(dir_ / "one.nff",
               "v\nfrom 0 0 10\nat 0 0 0\nup 0 1 0\nangle 10\nhither 1\nresolution 1 1\n"
               "l 0 0 10\nf 1 0.5 0.25 0.8 0.1 10 0 1\ns 0 0 0 1\n");
    const RunResult r = run_luz({"render", "one.nff", "-o", "one.pfm"}, dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    const std::string pfm = read_file(dir_ / "one.pfm");
    ASSERT_EQ(pfm.rfind("PF\n1 1\n-1", 0), 0u) << pfm.substr(0, 12);
    float rgb[3];
    ASSERT_GE(pfm.size(), sizeof rgb);
    std::memcpy(rgb, pfm.data() + pfm.size() - sizeof rgb, sizeof rgb);
    EXPECT_NEAR(rgb[0], 1.3f, 1.0f / 255);
    EXPECT_NEAR(rgb[1], 0.7f, 1.0f / 255);
    EXPECT_NEAR(rgb[2], 0.4f, 1.0f / 255);
}

TEST_F(NffCli, PortableAndAvx2KernelsRenderTheSameBits) {
    // LUZ_ISA=baseline: the portable scene queries even where the AVX2 ones would run
    // (geometry/query_isa.h); the same image bit for bit, on SPD scenes of every kind of
    // primitive (spheres and cylinders; cones; glass and mirror polygons).
    for (const char* name : {"rings", "tree", "gears"}) {
        const std::string nff = std::string(LUZ_SOURCE_DIR) + "/scenes/spd/" + name + ".nff";
        const std::vector<std::string> args = {"render",   nff,  "--width", "64",
                                               "--height", "64", "-o"};
        auto with = args;
        with.push_back("default.pfm");
        ASSERT_EQ(run_luz(with, dir_).status, 0);
        setenv("LUZ_ISA", "baseline", 1);
        auto without = args;
        without.push_back("baseline.pfm");
        const RunResult r = run_luz(without, dir_);
        unsetenv("LUZ_ISA");
        ASSERT_EQ(r.status, 0) << r.err;
        EXPECT_EQ(read_file(dir_ / "default.pfm"), read_file(dir_ / "baseline.pfm")) << name;
    }
}

}  // namespace
}  // namespace luz::test
