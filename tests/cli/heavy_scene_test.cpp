// Heavy scenes (scenes/exploding_glass.json: the ray tree grows as 2^depth, seconds a pixel):
// Ctrl-C ends luz within a second however long one pixel takes, the progress bar moves before
// the first tile is done, and luz says once that the tree explodes, naming render.min_weight.
#include <poll.h>
#include <pty.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <regex>
#include <set>
#include <thread>

#include "cli/run_luz.h"

namespace luz::test {
namespace {

using Clock = std::chrono::steady_clock;
const std::string kScene = LUZ_SOURCE_DIR "/scenes/exploding_glass.json";

class HeavyScene : public TempDirTest {};

/// The distinct progress lines ("0.04%  ETA 3h05m", the words after the bar) that `luz args`
/// draws on a terminal within `seconds`; stops reading at `enough` of them, then kills luz.
std::set<std::string> progress_lines_within(const std::vector<std::string>& args,
                                            const std::filesystem::path& cwd, double seconds,
                                            size_t enough) {
    std::string binary = LUZ_BINARY;
    std::vector<std::string> all = {binary};
    all.insert(all.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (const std::string& a : all) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    int master = -1;
    const pid_t pid = forkpty(&master, nullptr, nullptr, nullptr);
    if (pid < 0) return {};
    if (pid == 0) {
        if (chdir(cwd.c_str()) != 0) _exit(126);
        execv(binary.c_str(), argv.data());
        _exit(127);
    }
    const auto end = Clock::now() + std::chrono::duration<double>(seconds);
    const std::regex line(R"(\] ([^\r\x1b]*)\x1b\[K)");  // "\r[###---] WORDS\033[K"
    std::string text;
    std::set<std::string> lines;
    char buf[4096];
    while (lines.size() < enough && Clock::now() < end) {
        pollfd fd{master, POLLIN, 0};
        const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(end - Clock::now());
        if (poll(&fd, 1, static_cast<int>(std::max<long>(left.count(), 0))) <= 0) continue;
        const ssize_t n = read(master, buf, sizeof buf);
        if (n <= 0) break;  // luz ended
        text.append(buf, static_cast<size_t>(n));
        lines.clear();
        for (auto it = std::sregex_iterator(text.begin(), text.end(), line);
             it != std::sregex_iterator(); ++it)
            lines.insert((*it)[1]);
    }
    kill(pid, SIGKILL);
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    close(master);
    return lines;
}

TEST_F(HeavyScene, SigintStopsAnExplodingRayTreeWithinASecond) {
    std::string binary = LUZ_BINARY;
    const std::vector<std::string> args = {binary, "render", kScene, "-o", "out.png", "-q"};
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    const pid_t pid = fork();
    if (pid == 0) {
        if (chdir(dir_.c_str()) != 0) _exit(126);
        freopen("/dev/null", "w", stderr);
        execv(binary.c_str(), argv.data());
        _exit(127);
    }
    // Long enough for both threads to be deep inside exploding pixels (one takes seconds).
    std::this_thread::sleep_for(std::chrono::milliseconds(1500));
    const auto sent = Clock::now();
    kill(pid, SIGINT);
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    const double seconds = std::chrono::duration<double>(Clock::now() - sent).count();
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 130);
    EXPECT_LT(seconds, 1.0) << "took " << seconds << " s";
    EXPECT_TRUE(list_dir(dir_).empty());
    RecordProperty("interrupt_seconds", std::to_string(seconds));
}

TEST_F(HeavyScene, ProgressMovesWithinATileAndTheExplosionIsNamedOnce) {
    // One 16×16 tile: progress by finished tiles would show only 0 % and 100 %, and by runs of
    // 64 pixels (kRaysRun, render/ray_colour.h) at most three values between; heavy pixels go
    // one at a time (kHeavySampleRays), and the bar (drawn at most every 0.1 s) moves through a
    // second or more.
    const RunResult r = run_luz_on_terminal({"render", kScene, "--width", "16", "--height", "16",
                                             "--set", "render.max_depth=17", "-o", "out.png"},
                                            dir_);
    ASSERT_EQ(r.status, 0) << r.out;
    std::vector<double> percents;
    const std::regex bar(R"(\] +([0-9.]+)%)");
    for (auto it = std::sregex_iterator(r.out.begin(), r.out.end(), bar);
         it != std::sregex_iterator(); ++it)
        percents.push_back(std::stod((*it)[1]));
    ASSERT_GE(percents.size(), 4u) << r.out;
    int between = 0;
    for (size_t k = 0; k < percents.size(); ++k) {
        between += percents[k] > 0 && percents[k] < 100;
        if (k) {
            EXPECT_GE(percents[k], percents[k - 1]) << r.out;
        }
    }
    EXPECT_GE(between, 4) << r.out;
    // Said once, naming the key to set and max_depth.
    const std::string warning = "luz: warning: a sample traced ";
    const size_t at = r.out.find(warning);
    ASSERT_NE(at, std::string::npos) << r.out;
    EXPECT_EQ(r.out.find(warning, at + 1), std::string::npos) << "said once";
    EXPECT_NE(r.out.find("render.min_weight", at), std::string::npos);
    EXPECT_NE(r.out.find("render.max_depth 17", at), std::string::npos);
}

TEST_F(HeavyScene, ProgressSaysSomethingNewWithinSixSecondsAtFullSize) {
    LUZ_SPEED_TEST();
    // 320×240 pixels of seconds each (max_depth 22): the share shown with decimals and the
    // time left from the first pixel on give three different lines within the first 6 s
    // (it was "0%  ETA --" for the first 40 s).
    const std::set<std::string> lines =
        progress_lines_within({"render", kScene, "-o", "out.png"}, dir_, 6, 3);
    std::string all;
    for (const std::string& l : lines) all += "\n  " + l;
    EXPECT_GE(lines.size(), 3u) << "lines:" << all;
    for (const std::string& l : lines) EXPECT_EQ(l.find("ETA --"), std::string::npos) << all;
}

TEST_F(HeavyScene, MinWeightMakesItCheapAndQuiet) {
    const auto start = Clock::now();
    const RunResult r = run_luz({"render", kScene, "--width", "64", "--height", "48", "--set",
                                 "render.min_weight=0.05", "-o", "out.png", "-q"},
                                dir_);
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err, "") << "no warning once min_weight is set";
    EXPECT_LT(std::chrono::duration<double>(Clock::now() - start).count(), 30.0);
}

}  // namespace
}  // namespace luz::test
