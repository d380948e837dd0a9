// Interruption: SIGINT or SIGTERM during `luz render` stops it within a second, with exit status
// 128 + signal, "luz: interrupted", and no output, statistics or temporary file left behind.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <thread>

#include "cli/run_luz.h"

namespace luz::test {
namespace {

using Clock = std::chrono::steady_clock;

struct Interrupted {
    int status = -1;       ///< exit status (128 + signal when killed by it)
    double seconds = 1e9;  ///< from the signal to the exit
    std::string err;       ///< standard error
};

/// Starts luz with `args` in `cwd`, sends `sig` after `delay`, waits for the exit.
Interrupted render_and_signal(const std::vector<std::string>& args,
                              const std::filesystem::path& cwd, int sig,
                              std::chrono::milliseconds delay) {
    std::string binary = LUZ_BINARY;
    std::vector<char*> argv{binary.data()};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    const std::filesystem::path err_path = cwd.parent_path() / (cwd.filename().string() + ".err");
    const pid_t pid = fork();
    if (pid == 0) {
        if (chdir(cwd.c_str()) != 0) _exit(126);
        const int null_fd = open("/dev/null", O_RDWR);
        const int err_fd = open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        dup2(null_fd, STDIN_FILENO);
        dup2(null_fd, STDOUT_FILENO);
        dup2(err_fd, STDERR_FILENO);
        execv(binary.c_str(), argv.data());
        _exit(127);
    }
    Interrupted r;
    std::this_thread::sleep_for(delay);
    const auto sent = Clock::now();
    kill(pid, sig);
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    r.seconds = std::chrono::duration<double>(Clock::now() - sent).count();
    r.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    r.err = read_file(err_path);
    std::filesystem::remove(err_path);
    return r;
}

// A render long enough to be under way after 0.3 s, even in Release on a fast machine.
const std::vector<std::string> kLongRender = {"render",    "demo:whitted", "--width",   "2000",
                                              "--height",  "2000",         "--aa",      "grid",
                                              "--samples", "16",           "-o",        "out.png",
                                              "--stats",   "stats.json",   "--aa-mask", "mask.png"};

class InterruptTest : public TempDirTest {};

TEST_F(InterruptTest, SigintStopsWithinASecondAndLeavesNoFile) {
    const Interrupted r =
        render_and_signal(kLongRender, dir_, SIGINT, std::chrono::milliseconds(300));
    EXPECT_EQ(r.status, 130) << r.err;
    EXPECT_LT(r.seconds, 1.0);
    EXPECT_EQ(r.err, "luz: interrupted\n");
    EXPECT_TRUE(list_dir(dir_).empty()) << *list_dir(dir_).begin();
}

TEST_F(InterruptTest, SigtermLeavesAnExistingOutputUntouched) {
    write_file(dir_ / "out.png", "the previous picture");
    write_file(dir_ / "stats.json", "{}");
    const Interrupted r =
        render_and_signal(kLongRender, dir_, SIGTERM, std::chrono::milliseconds(300));
    EXPECT_EQ(r.status, 143) << r.err;
    EXPECT_LT(r.seconds, 1.0);
    EXPECT_EQ(r.err, "luz: interrupted\n");
    EXPECT_EQ(list_dir(dir_), (std::set<std::string>{"out.png", "stats.json"}));
    EXPECT_EQ(read_file(dir_ / "out.png"), "the previous picture");
    EXPECT_EQ(read_file(dir_ / "stats.json"), "{}");
}

}  // namespace
}  // namespace luz::test
