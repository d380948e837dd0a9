// luz's standard output: a reader gone away (`| head -1`) stops the printing, not the render
// (exit 0, every frame written); any other write error is exit 1 with one message.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "cli/run_luz.h"

namespace luz::test {
namespace {

namespace fs = std::filesystem;

class StandardOutput : public TempDirTest {
  protected:
    /// Runs luz in the test's folder with standard output on `out_fd` and standard error to
    /// the file "stderr.txt" (read into `err`); returns the exit status (128 + signal).
    int run_with_stdout(const std::vector<std::string>& args, int out_fd, std::string& err) {
        std::string binary = LUZ_BINARY;
        std::vector<char*> argv{binary.data()};
        for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
        argv.push_back(nullptr);
        const std::string err_path = (dir_ / "stderr.txt").string();
        const pid_t pid = fork();
        if (pid == 0) {
            if (chdir(dir_.c_str()) != 0) _exit(126);
            const int err_fd = open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
            dup2(err_fd, STDERR_FILENO);
            if (out_fd >= 0) {
                dup2(out_fd, STDOUT_FILENO);
            } else {
                close(STDOUT_FILENO);
            }
            execv(binary.c_str(), argv.data());
            _exit(127);
        }
        int status = 0;
        waitpid(pid, &status, 0);
        err = read_file(err_path);
        fs::remove(err_path);
        return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    }
};

// `luz render … --frames 0:10 | head -1` died of SIGPIPE after frame 1 (exit 141, frames 2–9
// never rendered). Here the pipe has no reader at all from the start: every line fails.
TEST_F(StandardOutput, ReaderGoneAwayStopsThePrintingNotTheFrames) {
    int fds[2];
    ASSERT_EQ(pipe(fds), 0);
    close(fds[0]);
    std::string err;
    const int status = run_with_stdout({"render", "demo:highlight", "--frames", "0:10", "--width",
                                        "16", "--height", "12", "-o", "h.png"},
                                       fds[1], err);
    close(fds[1]);
    EXPECT_EQ(status, 0) << err;
    EXPECT_EQ(err, "");
    std::set<std::string> frames;
    for (int f = 0; f < 10; ++f) frames.insert("h.000" + std::to_string(f) + ".png");
    EXPECT_EQ(list_dir(dir_), frames);
}

// `luz scenes > /dev/full` exited 0.
TEST_F(StandardOutput, FullDeviceIsExitOneWithAMessage) {
    const int full = open("/dev/full", O_WRONLY);
    if (full < 0) GTEST_SKIP() << "no /dev/full";
    for (const std::vector<std::string>& args :
         {std::vector<std::string>{"scenes"}, std::vector<std::string>{"materials"},
          std::vector<std::string>{"render", "demo:primitives", "--width", "8", "--height", "8",
                                   "-o", "x.png"}}) {
        std::string err;
        EXPECT_EQ(run_with_stdout(args, full, err), 1) << args[0];
        EXPECT_EQ(err, "luz: standard output: cannot write: No space left on device\n") << args[0];
    }
    close(full);
}

TEST_F(StandardOutput, ClosedStandardOutputIsExitOneWithAMessage) {
    std::string err;
    EXPECT_EQ(run_with_stdout({"scenes"}, -1, err), 1);
    EXPECT_EQ(err, "luz: standard output: cannot write: Bad file descriptor\n");
}

}  // namespace
}  // namespace luz::test
