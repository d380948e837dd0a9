// Interruption: SIGINT or SIGTERM during `luz render` stops it within a second, with exit status
// 128 + signal, "luz: interrupted", and no output, statistics or temporary file left behind —
// also while the image is being encoded.
#include <signal.h>

#include <chrono>

#include "cli/signal_luz.h"

namespace luz::test {
namespace {

// A render long enough to be under way after 0.3 s, even in Release on a fast machine.
const std::vector<std::string> kLongRender = {"render",    "demo:whitted", "--width",   "2000",
                                              "--height",  "2000",         "--aa",      "grid",
                                              "--samples", "16",           "-o",        "out.png",
                                              "--stats",   "stats.json",   "--aa-mask", "mask.png"};

class InterruptTest : public TempDirTest {};

TEST_F(InterruptTest, SigintStopsWithinASecondAndLeavesNoFile) {
    const Signalled r = signal_luz(kLongRender, dir_, SIGINT, after_seconds(0.3));
    ASSERT_TRUE(r.sent) << r.err;
    EXPECT_EQ(r.status, 130) << r.err;
    EXPECT_LT(r.seconds, 1.0);
    EXPECT_EQ(r.err, "luz: interrupted\n");
    EXPECT_TRUE(list_dir(dir_).empty()) << *list_dir(dir_).begin();
}

TEST_F(InterruptTest, SigtermLeavesAnExistingOutputUntouched) {
    write_file(dir_ / "out.png", "the previous picture");
    write_file(dir_ / "stats.json", "{}");
    const Signalled r = signal_luz(kLongRender, dir_, SIGTERM, after_seconds(0.3));
    ASSERT_TRUE(r.sent) << r.err;
    EXPECT_EQ(r.status, 143) << r.err;
    EXPECT_LT(r.seconds, 1.0);
    EXPECT_EQ(r.err, "luz: interrupted\n");
    EXPECT_EQ(list_dir(dir_), (std::set<std::string>{"out.png", "stats.json"}));
    EXPECT_EQ(read_file(dir_ / "out.png"), "the previous picture");
    EXPECT_EQ(read_file(dir_ / "stats.json"), "{}");
}

TEST_F(InterruptTest, SigintWhileAnExrIsEncodedStopsWithinASecond) {
    // A plane filling a 2560² image: rendered in a fraction of a second, then seconds of ZIP
    // compression of its 79 MB. The small mask is encoded and written to its temporary file
    // first: once that file is there, the render is over and the EXR is being encoded.
    write_file(dir_ / "plane.json", R"({
        "image": {"width": 2560, "height": 2560},
        "camera": {"projection": "perspective", "position": [0, 3, 0.5], "look_at": [0, 0, 0]},
        "render": {"pipeline": "zbuffer"},
        "lights": [{"position": [0.3, 0.5, 0.2], "intensity": 3}],
        "objects": [{"type": "plane", "material": {"kd": 0.7, "ks": 0.4, "n": 7}}]
    })");
    const Signalled r =
        signal_luz({"render", "plane.json", "-o", "big.exr", "--aa-mask", "mask.png"}, dir_, SIGINT,
                   [this] { return has_entry_containing(dir_, ".mask.png.tmp."); });
    ASSERT_TRUE(r.sent) << r.err;
    EXPECT_EQ(r.status, 130) << r.err;
    EXPECT_LT(r.seconds, 1.0);
    EXPECT_EQ(r.err, "luz: interrupted\n");
    EXPECT_EQ(list_dir(dir_), (std::set<std::string>{"plane.json"}));
}

}  // namespace
}  // namespace luz::test
