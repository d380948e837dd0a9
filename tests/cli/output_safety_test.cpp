// `luz render` never destroys what is not its outputs' own previous version: devices, FIFOs and
// descriptors are written as streams, symlinks written through, modes kept, folders refused,
// two names for one file refused before any work, all outputs committed together.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "cli/run_luz.h"
#include "fifo_reader.h"

namespace luz::test {
namespace {

namespace fs = std::filesystem;

class OutputSafety : public TempDirTest {
  protected:
    /// demo:primitives, small, with `extra` options.
    RunResult render(std::vector<std::string> extra, const std::string& scene = "demo:primitives") {
        std::vector<std::string> args = {"render", scene, "--width", "32", "--height", "24"};
        args.insert(args.end(), extra.begin(), extra.end());
        return run_luz(args, dir_);
    }
    mode_t mode_of(const std::string& name) const {
        struct stat st {};
        return ::lstat((dir_ / name).c_str(), &st) == 0 ? st.st_mode : 0;
    }
};

// As root, `--stats /dev/null` turned the device into a JSON file. Here a twin of /dev/null in
// the test's folder: tests never name the machine's devices (/dev/null, /dev/full,
// /dev/stdout), so that a regression cannot replace them.
TEST_F(OutputSafety, DeviceStaysADevice) {
    if (::mknod((dir_ / "null.json").c_str(), S_IFCHR | 0666, makedev(1, 3)) != 0 ||
        ::mknod((dir_ / "null.png").c_str(), S_IFCHR | 0666, makedev(1, 3)) != 0)
        GTEST_SKIP() << "cannot make a device node here (not root)";
    const RunResult r = render({"-o", "null.png", "--stats", "null.json"});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(S_ISCHR(mode_of("null.json")));
    EXPECT_TRUE(S_ISCHR(mode_of("null.png")));
    EXPECT_EQ(list_dir(dir_), (std::set<std::string>{"null.json", "null.png"}));
}

// `--stats /dev/stdout`: a symlink to /proc/self/fd/1, as /dev/stdout is.
TEST_F(OutputSafety, StatsToStandardOutputComeBeforeTheWroteLine) {
    fs::create_symlink("/proc/self/fd/1", dir_ / "stdout");
    const RunResult r = render({"-o", "x.png", "--stats", "stdout"});
    ASSERT_EQ(r.status, 0) << r.err;
    const size_t wrote = r.out.find("wrote x.png");
    ASSERT_NE(wrote, std::string::npos) << r.out;
    const auto stats = nlohmann::json::parse(r.out.substr(0, wrote));
    EXPECT_EQ(stats.at("width"), 32);
    EXPECT_EQ(list_dir(dir_), (std::set<std::string>{"stdout", "x.png"}));
    EXPECT_TRUE(S_ISLNK(mode_of("stdout")));
}

// `--stats >(cmd)`: a pipe at /dev/fd/N.
TEST_F(OutputSafety, StatsToAPipeAtDevFd) {
    const RunResult r = run_program(
        "/bin/sh",
        {"-c",
         "\"$0\" render demo:primitives --width 32 --height 24 -o x.png --stats /dev/fd/3 "
         "3>&1 >/dev/null | cat",
         LUZ_BINARY},
        dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(nlohmann::json::parse(r.out).at("height"), 24) << r.out;
    EXPECT_EQ(list_dir(dir_), std::set<std::string>{"x.png"});
}

TEST_F(OutputSafety, FifoIsStreamedToItsReaderAndStays) {
    ASSERT_EQ(::mkfifo((dir_ / "s.json").c_str(), 0600), 0);
    FifoReader reader(dir_ / "s.json");
    const RunResult r = render({"-o", "x.png", "--stats", "s.json"});
    const std::string got = reader.finish();
    ASSERT_EQ(r.status, 0) << r.err;
    ASSERT_FALSE(got.empty());
    EXPECT_EQ(nlohmann::json::parse(got).at("width"), 32);
    EXPECT_TRUE(S_ISFIFO(mode_of("s.json")));
}

TEST_F(OutputSafety, SymlinkIsWrittenThroughAndModeKept) {
    fs::create_directory(dir_ / "store");
    write_file(dir_ / "store/real.png", "old");
    ASSERT_EQ(::chmod((dir_ / "store/real.png").c_str(), 0600), 0);
    fs::create_symlink("store/real.png", dir_ / "link.png");
    const RunResult r = render({"-o", "link.png"});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(S_ISLNK(mode_of("link.png")));
    EXPECT_EQ(read_file(dir_ / "store/real.png").substr(1, 3), "PNG");
    EXPECT_EQ(mode_of("store/real.png") & 07777, 0600u);
    EXPECT_EQ(list_dir(dir_ / "store"), std::set<std::string>{"real.png"});
}

TEST_F(OutputSafety, HardLinkedOutputLeavesTheOtherNameItsOldVersion) {
    write_file(dir_ / "a.png", "old");
    fs::create_hard_link(dir_ / "a.png", dir_ / "b.png");
    const RunResult r = render({"-o", "a.png"});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(read_file(dir_ / "a.png").substr(1, 3), "PNG");
    EXPECT_EQ(read_file(dir_ / "b.png"), "old");
}

// A term's file that is a folder: refused before the render, the image left as it was (it was
// replaced, then the render failed with exit 1).
TEST_F(OutputSafety, FolderAmongTheOutputsIsBadInputBeforeAnyWork) {
    write_file(dir_ / "a.png", "OLD");
    fs::create_directory(dir_ / "a.depth.png");
    const RunResult r = render({"-o", "a.png", "--aov", "depth,normal"}, "demo:whitted");
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_EQ(r.err, "a.depth.png: --aov depth: is a folder, not a file\n");
    EXPECT_EQ(read_file(dir_ / "a.png"), "OLD");
    EXPECT_EQ(list_dir(dir_), (std::set<std::string>{"a.png", "a.depth.png"}));
}

// The statistics are committed with the image: a --stats that cannot be written leaves the
// existing image as it was.
TEST_F(OutputSafety, FailedStatsLeaveTheImageAsItWas) {
    if (::mknod((dir_ / "full.json").c_str(), S_IFCHR | 0666, makedev(1, 7)) != 0)
        GTEST_SKIP() << "cannot make a device node here (not root)";
    write_file(dir_ / "a.png", "OLD");
    const RunResult r = render({"-o", "a.png", "--stats", "full.json"});
    EXPECT_EQ(r.status, 1);
    EXPECT_EQ(r.err, "luz: full.json: cannot write: No space left on device\n");
    EXPECT_EQ(read_file(dir_ / "a.png"), "OLD");
    EXPECT_EQ(list_dir(dir_), (std::set<std::string>{"a.png", "full.json"}));
    EXPECT_TRUE(S_ISCHR(mode_of("full.json")));
}

struct Collision {
    std::vector<std::string> args;  ///< after the scene
    std::string message;            ///< the whole error line
};

// Two names for one file: exit 2 before any work, naming both; every file as it was.
TEST_F(OutputSafety, TwoNamesForOneFileAreBadInput) {
    write_file(dir_ / "sc.json", R"({"objects": [{"type": "mesh", "file": "m.obj"}]})");
    write_file(dir_ / "m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n");
    write_file(dir_ / "m.mtl", "newmtl a\nKd 1 0 0\n");
    write_file(dir_ / "a.png", "OLD");
    fs::create_hard_link(dir_ / "a.png", dir_ / "hard.json");
    fs::create_symlink("a.png", dir_ / "soft.json");
    const std::vector<Collision> cases = {
        {{"-o", "s.png", "--checkpoint", "s.png"}, "s.png: -o and --checkpoint name the same file"},
        {{"-o", "a.png", "--stats", "a.png"}, "a.png: -o and --stats name the same file"},
        {{"-o", "b.png", "--aa-mask", "b.png"}, "b.png: -o and --aa-mask name the same file"},
        {{"-o", "b.png", "--aov", "depth", "--aa-mask", "./b.depth.png"},
         "b.depth.png: --aov depth and --aa-mask name the same file (./b.depth.png)"},
        {{"-o", "a.png", "--stats", "hard.json"},
         "a.png: -o and --stats name the same file (hard.json)"},
        {{"-o", "a.png", "--stats", "soft.json"},
         "a.png: -o and --stats name the same file (soft.json)"},
        {{"-o", "x.png", "--stats", "sc.json"},
         "sc.json: --stats and the scene file name the same file"},
        {{"-o", "x.png", "--stats", "m.obj"},
         "m.obj: --stats and the scene's mesh or MTL file name the same file"},
        {{"-o", "x.png", "--checkpoint", "m.mtl"},
         "m.mtl: --checkpoint and the scene's mesh or MTL file name the same file"},
    };
    const std::set<std::string> before = list_dir(dir_);
    for (const Collision& c : cases) {
        const RunResult r = render(c.args, "sc.json");
        EXPECT_EQ(r.status, 2) << c.message << ": " << r.err;
        EXPECT_EQ(r.err, c.message + "\n");
        EXPECT_EQ(list_dir(dir_), before) << c.message;
    }
    EXPECT_EQ(read_file(dir_ / "a.png"), "OLD");
    EXPECT_EQ(read_file(dir_ / "sc.json").substr(0, 12), R"({"objects": )");
    EXPECT_EQ(read_file(dir_ / "m.mtl"), "newmtl a\nKd 1 0 0\n");
}

TEST_F(OutputSafety, FramesCollideWithOtherOutputs) {
    const RunResult r = run_luz({"render", "demo:highlight", "--width", "16", "--height", "12",
                                 "--frames", "0:3", "-o", "h.png", "--stats", "h.0002.png"},
                                dir_);
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_EQ(r.err, "h.0002.png: -o and --stats name the same file\n");
    EXPECT_TRUE(list_dir(dir_).empty());
}

}  // namespace
}  // namespace luz::test
