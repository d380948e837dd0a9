// `luz render --frames A:B|all` (docs/CLI.md) of scenes with an `animation`
// (docs/SCENES.md#scene-files): one file per frame X.0000.EXT (per-term images and masks too),
// --stats totals and frames, each frame the scene with its keyed values set, bad ranges and bad
// animations exit 2 leaving no file, and an interrupted sequence keeps the frames already written.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "cli/run_luz.h"

namespace luz::test {
namespace {

class AnimationCli : public TempDirTest {};

// A small raytraced scene; with kAnimation, frame 3 has n = 2 + 32·3/4 = 26 and the light at
// (−4 + 8·3/4, 5, 5 − 4·3/4) = (2, 5, 2): numbers written exactly in binary.
const char* const kStill = R"({
  "image": {"width": 40, "height": 30},
  "camera": {"projection": "perspective", "position": [0, 1.5, 6], "look_at": [0, 0.8, 0]},
  "render": {"pipeline": "raytrace"},
  "materials": {"red": {"ka": 0.1, "kd": [0.7, 0.1, 0.1], "ks": 0.4, "n": 2, "reflection": 0.2}},
  "lights": [{"position": [-4, 5, 5], "intensity": 9}],
  "objects": [{"type": "plane", "material": "gesso"},
              {"type": "sphere", "center": [0, 1, 0], "material": "red"}])";
const char* const kAnimation = R"(,
  "animation": {"frames": 5, "fps": 10, "keys": {
    "materials.red.n": [[0, 2], [4, 34]],
    "lights.0.position": [[0, [-4, 5, 5]], [4, [4, 5, 1]]]}}
})";

// (appended, not `std::string(…) + …`: g++ 12 at -O1 warns of a false -Warray-bounds there)
std::string still_plus(const char* tail) {
    std::string text = kStill;
    text += tail;
    return text;
}
std::string animated_scene() { return still_plus(kAnimation); }
std::string still_scene() { return still_plus("\n}"); }

std::vector<std::string> highlight(std::vector<std::string> extra) {
    std::vector<std::string> a = {"render", "demo:highlight", "--width", "32", "--height", "24"};
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
}

TEST_F(AnimationCli, RangeWritesExactlyItsFrames) {
    const RunResult r = run_luz(highlight({"--frames", "2:5", "-o", "x.png"}), dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(list_dir(dir_), (std::set<std::string>{"x.0002.png", "x.0003.png", "x.0004.png"}));
    // One line per frame written, then the summary.
    EXPECT_NE(r.out.find("wrote x.0002.png\nwrote x.0003.png\nwrote x.0004.png\n"),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("wrote 3 frames x.0002.png … x.0004.png (32×24, raycast"),
              std::string::npos)
        << r.out;
    EXPECT_EQ(count_lines(r.out), 4) << r.out;
    // The frames differ (n and the light change).
    EXPECT_NE(read_file(dir_ / "x.0002.png"), read_file(dir_ / "x.0004.png"));
}

TEST_F(AnimationCli, AllWritesEveryFrameOfASceneFile) {
    write_file(dir_ / "anim.json", animated_scene());
    const RunResult r = run_luz({"render", "anim.json", "--frames", "all", "-q"}, dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.out, "");
    // The default output is the scene's name.
    EXPECT_EQ(list_dir(dir_),
              (std::set<std::string>{"anim.json", "anim.0000.png", "anim.0001.png", "anim.0002.png",
                                     "anim.0003.png", "anim.0004.png"}));
}

TEST_F(AnimationCli, PerTermImagesAndMasksAreNumberedToo) {
    const RunResult r =
        run_luz(highlight({"--frames", "2:4", "-o", "x.png", "--aov", "depth,diffuse", "--aa",
                           "adaptive", "--aa-mask", "m.png", "-q"}),
                dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(list_dir(dir_),
              (std::set<std::string>{"x.0002.png", "x.0002.depth.png", "x.0002.diffuse.png",
                                     "m.0002.png", "x.0003.png", "x.0003.depth.png",
                                     "x.0003.diffuse.png", "m.0003.png"}));
}

TEST_F(AnimationCli, StatsHoldTheTotalsAndEachFrame) {
    const RunResult r =
        run_luz(highlight({"--frames", "2:5", "-o", "x.png", "--stats", "s.json", "-q"}), dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    const auto s = nlohmann::json::parse(read_file(dir_ / "s.json"));
    ASSERT_TRUE(s["frames"].is_array());
    ASSERT_EQ(s["frames"].size(), 3u);
    uint64_t primary = 0, tests = 0;
    double seconds = 0;
    for (int i = 0; i < 3; ++i) {
        const auto& f = s["frames"][i];
        EXPECT_EQ(f["frame"], 2 + i);
        EXPECT_EQ(f["width"], 32);
        EXPECT_EQ(f["rays"]["primary"], 32 * 24);
        primary += f["rays"]["primary"].get<uint64_t>();
        tests += f["intersection_tests"]["primitive"].get<uint64_t>();
        seconds += f["seconds"].get<double>();
    }
    EXPECT_EQ(s["rays"]["primary"], primary);
    EXPECT_EQ(s["intersection_tests"]["primitive"], tests);
    EXPECT_NEAR(s["seconds"].get<double>(), seconds, 1e-9);
    EXPECT_EQ(s["width"], 32);
    EXPECT_EQ(s["height"], 24);
    EXPECT_EQ(s["pipeline"], "raycast");
    EXPECT_EQ(s["frame_range"], nlohmann::json::array({2, 5}));
    EXPECT_EQ(s["fps"], 24);
}

TEST_F(AnimationCli, FrameIsTheRenderWithItsKeyedValuesSet) {
    write_file(dir_ / "anim.json", animated_scene());
    write_file(dir_ / "still.json", still_scene());
    const RunResult r = run_luz({"render", "anim.json", "--frames", "3:4", "-o", "x.pfm", "--aov",
                                 "specular", "--threads", "2", "-q"},
                                dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    const RunResult ref = run_luz(
        {"render", "still.json", "--set", "materials.red.n=26", "--set",
         "lights.0.position=[2,5,2]", "-o", "ref.pfm", "--aov", "specular", "--threads", "2", "-q"},
        dir_);
    ASSERT_EQ(ref.status, 0) << ref.err;
    EXPECT_EQ(read_file(dir_ / "x.0003.pfm"), read_file(dir_ / "ref.pfm"));
    EXPECT_EQ(read_file(dir_ / "x.0003.specular.pfm"), read_file(dir_ / "ref.specular.pfm"));
    // Another frame is another image.
    const RunResult zero =
        run_luz({"render", "still.json", "-o", "zero.pfm", "--threads", "2", "-q"}, dir_);
    ASSERT_EQ(zero.status, 0) << zero.err;
    EXPECT_NE(read_file(dir_ / "x.0003.pfm"), read_file(dir_ / "zero.pfm"));
}

TEST_F(AnimationCli, SetWinsOverTheKeys) {
    // --set on an animated path holds it at every frame; the other keys still animate.
    write_file(dir_ / "anim.json", animated_scene());
    write_file(dir_ / "still.json", still_scene());
    ASSERT_EQ(run_luz({"render", "anim.json", "--frames", "3:4", "-o", "x.pfm", "--set",
                       "materials.red.n=900", "--set", "materials.red.ks=0.8", "-q"},
                      dir_)
                  .status,
              0);
    ASSERT_EQ(run_luz({"render", "still.json", "--set", "materials.red.n=900", "--set",
                       "lights.0.position=[2,5,2]", "--set", "materials.red.ks=0.8", "-o",
                       "ref.pfm", "-q"},
                      dir_)
                  .status,
              0);
    EXPECT_EQ(read_file(dir_ / "x.0003.pfm"), read_file(dir_ / "ref.pfm"));
}

TEST_F(AnimationCli, WithoutFramesTheFirstFrameIsRendered) {
    write_file(dir_ / "anim.json", animated_scene());
    write_file(dir_ / "still.json", still_scene());
    const RunResult r = run_luz({"render", "anim.json", "-o", "x.pfm"}, dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("wrote x.pfm (40×30, raytrace"), std::string::npos) << r.out;
    ASSERT_EQ(run_luz({"render", "still.json", "-o", "still.pfm", "-q"}, dir_).status, 0);
    ASSERT_EQ(run_luz({"render", "anim.json", "--frames", "0:1", "-o", "f.pfm", "-q"}, dir_).status,
              0);
    EXPECT_EQ(list_dir(dir_), (std::set<std::string>{"anim.json", "still.json", "x.pfm",
                                                     "still.pfm", "f.0000.pfm"}));
    EXPECT_EQ(read_file(dir_ / "x.pfm"), read_file(dir_ / "still.pfm"));
    EXPECT_EQ(read_file(dir_ / "x.pfm"), read_file(dir_ / "f.0000.pfm"));
}

TEST_F(AnimationCli, SameBitsWhateverTheThreadCount) {
    for (const char* threads : {"1", "2"}) {
        const RunResult r = run_luz(
            highlight({"--frames", "30:31", "--pipeline", "raytrace", "--aa", "adaptive", "-o",
                       std::string("t") + threads + ".pfm", "--threads", threads, "-q"}),
            dir_);
        ASSERT_EQ(r.status, 0) << r.err;
    }
    EXPECT_EQ(read_file(dir_ / "t1.0030.pfm"), read_file(dir_ / "t2.0030.pfm"));
}

/// `luz` with `args` must exit 2 with one line on standard error holding `message`, and write
/// nothing (the folder keeps only `kept`).
void expect_refused(const std::vector<std::string>& args, const std::filesystem::path& dir,
                    const std::string& message, const std::set<std::string>& kept = {}) {
    const RunResult r = run_luz(args, dir);
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(list_dir(dir), kept);
}

TEST_F(AnimationCli, FramesOfASceneWithoutAnimationAreRefused) {
    expect_refused({"render", "demo:primitives", "--frames", "0:1", "-o", "x.png"}, dir_,
                   "--frames 0:1: demo:primitives has no animation");
    expect_refused({"render", "demo:primitives", "--frames", "all", "-o", "x.png"}, dir_,
                   "--frames all: demo:primitives has no animation");
}

TEST_F(AnimationCli, BadRangesAreRefused) {
    expect_refused(highlight({"--frames", "0:999", "-o", "x.png"}), dir_,
                   "--frames 0:999: past the last frame: the scene has frames 0 to 47");
    expect_refused(highlight({"--frames", "5:5", "-o", "x.png"}), dir_,
                   "--frames 5:5: empty range");
    expect_refused(highlight({"--frames", "7", "-o", "x.png"}), dir_,
                   "--frames 7: expected A:B (frames A to B-1) or all");
    expect_refused(highlight({"--frames", "a:b", "-o", "x.png", "--stats", "s.json"}), dir_,
                   "--frames a:b: expected A:B");
}

TEST_F(AnimationCli, CheckpointIsRefusedWithFrames) {
    expect_refused(highlight({"--frames", "0:2", "-o", "x.png", "--checkpoint", "c.ckpt"}), dir_,
                   "--checkpoint: cannot be used with --frames");
}

TEST_F(AnimationCli, ABadAnimationKeyIsRefusedNamingIt) {
    write_file(dir_ / "bad.json", std::string(kStill) + R"(,
      "animation": {"frames": 3, "keys": {"materials.red.nn": [[0, 1], [2, 3]]}}})");
    expect_refused({"render", "bad.json", "--frames", "all", "-o", "x.png"}, dir_,
                   "bad.json: animation.keys.materials.red.nn at frame 0 = 1: materials.red.nn: "
                   "unknown key",
                   {"bad.json"});
    // Refused without --frames too: every frame is checked at load.
    write_file(dir_ / "bad.json", std::string(kStill) + R"(,
      "animation": {"frames": 8, "keys": {"materials.red.n": [[0, 1], [6, 1], [7, -3]]}}})");
    expect_refused({"render", "bad.json", "-o", "x.png"}, dir_,
                   "bad.json: animation.keys.materials.red.n at frame 7 = -3: materials.red.n: "
                   "must be > 0, got -3",
                   {"bad.json"});
    write_file(dir_ / "bad.json", std::string(kStill) + R"(,
      "animation": {"frames": 3, "keys": {"materials.red.n": [[2, 1], [1, 3]]}}})");
    expect_refused({"render", "bad.json", "-o", "x.png"}, dir_,
                   "bad.json: animation.keys.materials.red.n.1.0: keyframes must be in increasing "
                   "frame order",
                   {"bad.json"});
}

TEST_F(AnimationCli, EveryFrameIsCheckedForMemoryAndRegionBeforeAnyWork) {
    // Frame 0 is 16×16, frame 1 4000×4000: too large for the limit, refused before frame 0 is
    // written. The frames rendered are those checked.
    write_file(dir_ / "grow.json", R"({"render": {"pipeline": "raycast"},
      "objects": [{"type": "sphere"}],
      "animation": {"frames": 2, "keys": {"image.width": [[0, 16], [1, 4000]],
                                          "image.height": [[0, 16], [1, 4000]]}}})");
    expect_refused(
        {"render", "grow.json", "--frames", "all", "--max-memory", "100M", "-o", "x.png"}, dir_,
        "--frames all: frame 1: grow.json: image.width: 4000x4000 needs ", {"grow.json"});
    const RunResult first =
        run_luz({"render", "grow.json", "--max-memory", "100M", "-o", "x.png", "-q"}, dir_);
    EXPECT_EQ(first.status, 0) << first.err;
    std::filesystem::remove(dir_ / "x.png");
    // --region: inside frame 1, outside frame 0.
    expect_refused(
        {"render", "grow.json", "--frames", "all", "--region", "0,0,20,20", "-o", "x.png"}, dir_,
        "--region 0,0,20,20: outside the 16x16 image", {"grow.json"});
    const RunResult r = run_luz(
        {"render", "grow.json", "--frames", "1:2", "--region", "0,0,20,20", "-o", "x.png", "-q"},
        dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(list_dir(dir_), (std::set<std::string>{"grow.json", "x.0001.png"}));
    write_file(dir_ / "shrink.json", R"({"render": {"pipeline": "raycast"},
      "objects": [{"type": "sphere"}],
      "animation": {"frames": 2, "keys": {"image.width": [[0, 32], [1, 8]]}}})");
    expect_refused(
        {"render", "shrink.json", "--frames", "0:2", "--region", "0,0,16,16", "-o", "y.png"}, dir_,
        "--frames 0:2: frame 1: --region 0,0,16,16: outside the 8x600 image",
        {"grow.json", "x.0001.png", "shrink.json"});
}

TEST_F(AnimationCli, AnInterruptedSequenceKeepsTheFinishedFrames) {
    // Frame 0 is tiny, frame 1 takes seconds: interrupted during frame 1, frame 0 stays and
    // frame 1 leaves nothing (no file, no temporary file, no statistics).
    write_file(dir_ / "slow.json", std::string(kStill) + R"(,
      "animation": {"frames": 2, "keys": {"image.width": [[0, 8], [1, 3000]],
                                          "image.height": [[0, 8], [1, 3000]],
                                          "render.antialias.samples": [[0, 1], [1, 64]]}}})");
    std::string binary = LUZ_BINARY;
    std::vector<std::string> args = {"render",  "slow.json", "--frames",  "all",
                                     "--aa",    "grid",      "-o",        "x.png",
                                     "--stats", "s.json",    "--threads", "2"};
    std::vector<char*> argv{binary.data()};
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    const pid_t pid = fork();
    if (pid == 0) {
        if (chdir(dir_.c_str()) != 0) _exit(126);
        const int null_fd = open("/dev/null", O_RDWR);
        dup2(null_fd, STDIN_FILENO);
        dup2(null_fd, STDOUT_FILENO);
        dup2(null_fd, STDERR_FILENO);
        execv(binary.c_str(), argv.data());
        _exit(127);
    }
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (!std::filesystem::exists(dir_ / "x.0000.png") &&
           std::chrono::steady_clock::now() < deadline) {
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(200));  // into frame 1
    kill(pid, SIGINT);
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 130);
    EXPECT_EQ(list_dir(dir_), (std::set<std::string>{"slow.json", "x.0000.png"}));
}

}  // namespace
}  // namespace luz::test
