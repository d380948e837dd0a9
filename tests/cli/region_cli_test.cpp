// `luz render --region X0,Y0,X1,Y1` (docs/CLI.md): the file is X1−X0 by Y1−Y0 and its pixels are
// the same rectangle of the whole render; the per-term files and the mask are cut the same way;
// --stats names the region; a bad rectangle exits 2 naming --region and leaves no file.
#include <gtest/gtest.h>

#include <cstring>
#include <nlohmann/json.hpp>

#include "cli/run_luz.h"
#include "image/image_io.h"

namespace luz::test {
namespace {

class Region : public TempDirTest {};

const std::vector<std::string> kRegionScene = {"demo:whitted",
                                               "--width",
                                               "97",
                                               "--height",
                                               "71",
                                               "--aa",
                                               "grid",
                                               "--set",
                                               "render.antialias.filter=\"tent\"",
                                               "-q"};

std::vector<std::string> region_args(std::vector<std::string> extra) {
    std::vector<std::string> a = {"render"};
    a.insert(a.end(), kRegionScene.begin(), kRegionScene.end());
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
}

TEST_F(Region, FileIsTheRectangleOfTheWholeRender) {
    ASSERT_EQ(run_luz(region_args({"-o", "whole.pfm", "--aov", "depth"}), dir_).status, 0);
    const RunResult r = run_luz(region_args({"-o", "part.pfm", "--aov", "depth", "--region",
                                             "13,20,61,33", "--stats", "s.json"}),
                                dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    for (const char* suffix : {"", ".depth"}) {
        const Image whole = read_image((dir_ / (std::string("whole") + suffix + ".pfm")).string());
        const Image part = read_image((dir_ / (std::string("part") + suffix + ".pfm")).string());
        ASSERT_EQ(part.width, 48);
        ASSERT_EQ(part.height, 13);
        for (int y = 0; y < part.height; ++y)
            ASSERT_EQ(std::memcmp(&part.at(0, y), &whole.at(13, 20 + y), sizeof(Rgb) * 48), 0)
                << suffix << " row " << y;
    }
    const auto stats = nlohmann::json::parse(read_file(dir_ / "s.json"));
    EXPECT_EQ(stats["width"], 48);
    EXPECT_EQ(stats["height"], 13);
    EXPECT_EQ(stats["region"], nlohmann::json::array({13, 20, 61, 33}));
}

TEST_F(Region, AdaptiveMaskIsCutToo) {
    const RunResult r =
        run_luz({"render", "demo:whitted", "--width", "64", "--height", "48", "--aa", "adaptive",
                 "--region", "0,40,64,48", "-o", "p.png", "--aa-mask", "m.png", "-q"},
                dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    const Image mask = read_image((dir_ / "m.png").string());
    EXPECT_EQ(mask.width, 64);
    EXPECT_EQ(mask.height, 8);
}

TEST_F(Region, BadRectanglesExit2NamingTheOptionAndWriteNothing) {
    const std::pair<const char*, const char*> cases[] = {
        {"1,2,3", "--region 1,2,3: expected four integers X0,Y0,X1,Y1"},
        {"a,b,c,d", "--region a,b,c,d: expected four integers"},
        {"0,0,98,10", "--region 0,0,98,10: outside the 97x71 image"},
        {"-2,0,5,5", "--region -2,0,5,5: outside the 97x71 image"},
        {"5,5,5,9", "--region 5,5,5,9: the region is empty"},
        {"", "--region : expected four integers"},
    };
    for (const auto& [text, message] : cases) {
        const RunResult r = run_luz(region_args({"-o", "x.png", "--region", text}), dir_);
        EXPECT_EQ(r.status, 2) << text;
        EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
        EXPECT_EQ(count_lines(r.err), 1) << r.err;
        EXPECT_TRUE(list_dir(dir_).empty()) << text;
    }
}

}  // namespace
}  // namespace luz::test
