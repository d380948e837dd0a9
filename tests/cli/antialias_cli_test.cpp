// Antialiasing on the command line (docs/SCENES.md#antialiasing, docs/CLI.md): --aa, --samples,
// --threshold, the scene's render.antialias keys, --stats' pixels_refined and samples, and
// --aa-mask FILE.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "cli/run_luz.h"
#include "image/image_io.h"

namespace luz::test {
namespace {

class AntialiasCli : public TempDirTest {};

const std::vector<std::string> kSmall = {"--width", "160", "--height", "120"};

std::vector<std::string> args(std::vector<std::string> a, const std::vector<std::string>& more) {
    a.insert(a.end(), more.begin(), more.end());
    return a;
}

/// Pixels of a mask image that are not grey (refined ones are coloured by level).
size_t coloured_pixels(const Image& img) {
    size_t n = 0;
    for (const Rgb& c : img.pixels) n += !(c.x == c.y && c.y == c.z);
    return n;
}

TEST_F(AntialiasCli, AaMaskShowsTheRefinedPixelsCountedInStats) {
    for (const char* pipeline : {"zbuffer", "raycast", "raytrace"}) {
        const RunResult r = run_luz(
            args({"render", "demo:primitives", "-o", "x.png", "--aa", "adaptive", "--threshold",
                  "0.05", "--pipeline", pipeline, "--aa-mask", "mask.png", "--stats", "s.json"},
                 kSmall),
            dir_);
        ASSERT_EQ(r.status, 0) << r.err;
        const nlohmann::json j = nlohmann::json::parse(read_file(dir_ / "s.json"));
        const auto refined = j["pixels_refined"].get<uint64_t>();
        EXPECT_GT(refined, 0u);
        EXPECT_GT(j["samples"].get<uint64_t>(), 161u * 121u / 2) << "corners, then more";
        const Image mask = read_image((dir_ / "mask.png").string());
        EXPECT_EQ(mask.width, 160);
        EXPECT_EQ(mask.height, 120);
        EXPECT_EQ(coloured_pixels(mask), refined) << pipeline;
        EXPECT_EQ(list_dir(dir_), (std::set<std::string>{"mask.png", "s.json", "x.png"}));
    }
}

TEST_F(AntialiasCli, GridRefinesNoPixelAndCountsItsSamples) {
    const RunResult r =
        run_luz(args({"render", "demo:primitives", "-o", "x.png", "--aa", "grid", "--samples", "9",
                      "--pipeline", "raycast", "--aa-mask", "mask.pfm", "--stats", "s.json"},
                     kSmall),
                dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(read_file(dir_ / "s.json"));
    EXPECT_EQ(j["pixels_refined"].get<uint64_t>(), 0u);
    EXPECT_EQ(j["samples"].get<uint64_t>(), 9u * 160 * 120);
    EXPECT_EQ(j["rays"]["primary"].get<uint64_t>(), 9u * 160 * 120);
    EXPECT_EQ(coloured_pixels(read_image((dir_ / "mask.pfm").string())), 0u);
}

TEST_F(AntialiasCli, SceneKeysAndOptionsAgree) {
    write_file(dir_ / "s.json", R"({"render": {"pipeline": "raycast",
        "antialias": {"mode": "grid", "samples": 4, "filter": "tent", "jitter": true}},
        "image": {"width": 40, "height": 30}, "objects": [{"type": "sphere"}]})");
    ASSERT_EQ(run_luz({"render", "s.json", "-o", "a.pfm"}, dir_).status, 0);
    ASSERT_EQ(run_luz({"render", "s.json", "-o", "b.pfm", "--set", "render.antialias.mode=none",
                       "--aa", "grid", "--samples", "4"},
                      dir_)
                  .status,
              0);
    ASSERT_EQ(run_luz({"render", "s.json", "-o", "c.pfm", "--threads", "1"}, dir_).status, 0);
    EXPECT_EQ(read_file(dir_ / "a.pfm"), read_file(dir_ / "b.pfm"));
    EXPECT_EQ(read_file(dir_ / "a.pfm"), read_file(dir_ / "c.pfm"));
}

struct BadAa {
    std::vector<std::string> extra;
    std::string key;  ///< must appear in the one error line
};

class AntialiasBadInput : public TempDirTest, public testing::WithParamInterface<BadAa> {};

TEST_P(AntialiasBadInput, ExitsTwoNamingTheKeyAndLeavesNoFile) {
    const RunResult r =
        run_luz(args({"render", "demo:primitives", "-o", "x.png"}, GetParam().extra), dir_);
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(GetParam().key), std::string::npos) << r.err;
    EXPECT_TRUE(list_dir(dir_).empty());
}

INSTANTIATE_TEST_SUITE_P(
    Cases, AntialiasBadInput,
    testing::Values(BadAa{{"--aa", "grid", "--samples", "8"}, "--samples"},
                    BadAa{{"--samples", "0"}, "--samples"},
                    BadAa{{"--threshold", "-0.01"}, "--threshold"},
                    BadAa{{"--set", "render.antialias.max_level=7"}, "render.antialias.max_level"},
                    BadAa{{"--set", "render.antialias.samples=10"}, "render.antialias.samples"},
                    BadAa{{"--set", "render.antialias.threshold=-1"}, "render.antialias.threshold"},
                    BadAa{{"--set", "render.antialias.filter=gauss"}, "render.antialias.filter"},
                    BadAa{{"--aa", "adaptive", "--aa-mask", "mask.bmp"}, "--aa-mask"},
                    BadAa{{"--aa", "adaptive", "--aa-mask", "nodir/mask.png"}, "--aa-mask"}));

}  // namespace
}  // namespace luz::test
