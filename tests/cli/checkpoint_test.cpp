// --checkpoint FILE: an interrupted render keeps its finished tiles; reruns continue and end with
// the bits of an uninterrupted render (interrupted at random moments, several times in a row);
// the file is removed after success; a file of another render, a damaged one or not a
// checkpoint is refused with exit 2, the output untouched and the file left as it was.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <random>
#include <set>
#include <thread>

#include "cli/run_luz.h"

namespace luz::test {
namespace {

class Checkpoint : public TempDirTest {};

/// Runs luz with `args` in `cwd`, its checkpoint render.ckpt written every 0.02 s; sends SIGINT
/// `ms` milliseconds after a periodic write added tiles to the file (the render under way,
/// however fast the build; a fixed wait from the start would have to be longer than a slow
/// build's start-up and shorter than a fast build's render), unless it ended first; returns the
/// exit status.
int run_and_interrupt(const std::vector<std::string>& args, const std::filesystem::path& cwd,
                      int ms) {
    const auto size = [&] {  // 0 while there is no file
        std::error_code ec;
        const auto n = std::filesystem::file_size(cwd / "render.ckpt", ec);
        return ec ? 0 : n;
    };
    const auto before = size();
    std::string binary = LUZ_BINARY;
    std::vector<char*> argv{binary.data()};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    const pid_t pid = fork();
    if (pid == 0) {
        if (chdir(cwd.c_str()) != 0) _exit(126);
        setenv("LUZ_CHECKPOINT_SECONDS", "0.02", 1);
        freopen("/dev/null", "w", stderr);
        freopen("/dev/null", "w", stdout);
        execv(binary.c_str(), argv.data());
        _exit(127);
    }
    int status = 0;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    bool ended = false;
    while (size() <= before && std::chrono::steady_clock::now() < deadline &&
           !(ended = waitpid(pid, &status, WNOHANG) == pid)) {
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    if (!ended) {
        std::this_thread::sleep_for(std::chrono::milliseconds(ms));
        kill(pid, SIGINT);
        while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
        }
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

// About 0.3 s on two threads of an idle machine: each run is interrupted once it has saved
// some tiles, so the render need only outlast a few such runs.
std::vector<std::string> checkpoint_render(const std::string& out, const std::string& aa) {
    return {"render",  "demo:whitted", "--width", "640", "--height", "480",          "--aa",
            aa,        "--samples",    "9",       "-o",  out,        "--checkpoint", "render.ckpt",
            "--stats", "stats.json"};
}

/// Interrupts the render at random moments (0 to 50 ms after a run's first periodic write) four
/// times in a row, each run continuing from the checkpoint, then lets one more run finish.
void resume_until_done(const std::filesystem::path& dir, const std::string& aa, std::mt19937& rng) {
    const std::vector<std::string> args = checkpoint_render("resumed.png", aa);
    int interrupted = 0;
    for (int run = 0; run < 4; ++run) {
        const int ms = std::uniform_int_distribution<int>(0, 50)(rng);
        const int status = run_and_interrupt(args, dir, ms);
        if (status == 0) break;
        ASSERT_EQ(status, 130);
        ASSERT_TRUE(std::filesystem::exists(dir / "render.ckpt")) << "kept when interrupted";
        ASSERT_FALSE(std::filesystem::exists(dir / "resumed.png"));
        ++interrupted;
    }
    EXPECT_GE(interrupted, 2) << "interrupted at least twice before it finished";
    if (!std::filesystem::exists(dir / "resumed.png")) {
        const RunResult last = run_luz(args, dir);
        ASSERT_EQ(last.status, 0) << last.err;
    }
    ASSERT_TRUE(std::filesystem::exists(dir / "resumed.png"));
    EXPECT_FALSE(std::filesystem::exists(dir / "render.ckpt")) << "removed after success";
}

TEST_F(Checkpoint, ResumedRendersEndWithTheBitsOfAnUninterruptedOne) {
    std::mt19937 rng(12345);
    for (const std::string aa : {"grid", "adaptive"}) {
        std::vector<std::string> plain = checkpoint_render("plain.png", aa);
        plain.resize(plain.size() - 4);  // no --checkpoint, no --stats
        plain.push_back("-q");
        const RunResult r = run_luz(plain, dir_);
        ASSERT_EQ(r.status, 0) << r.err;
        resume_until_done(dir_, aa, rng);
        EXPECT_EQ(read_file(dir_ / "resumed.png"), read_file(dir_ / "plain.png")) << aa;
        std::filesystem::remove(dir_ / "resumed.png");
    }
}

TEST_F(Checkpoint, AnotherRendersFileIsRefusedAndLeftAsItWas) {
    ASSERT_EQ(run_and_interrupt(checkpoint_render("out.png", "grid"), dir_, 0), 130);
    const std::string saved = read_file(dir_ / "render.ckpt");
    write_file(dir_ / "other.png", "the previous picture");
    std::vector<std::string> other = checkpoint_render("other.png", "grid");
    other.push_back("--set");
    other.push_back("materials.mirror.reflection=0.5");
    const RunResult r = run_luz(other, dir_);
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.err,
              "render.ckpt: --checkpoint: made for another scene or other options (render again "
              "without it, or remove the file)\n");
    EXPECT_EQ(read_file(dir_ / "render.ckpt"), saved);
    EXPECT_EQ(read_file(dir_ / "other.png"), "the previous picture");
}

TEST_F(Checkpoint, DamagedOrForeignFilesAreRefused) {
    ASSERT_EQ(run_and_interrupt(checkpoint_render("out.png", "grid"), dir_, 0), 130);
    const std::string saved = read_file(dir_ / "render.ckpt");
    ASSERT_GT(saved.size(), 100u);
    struct Case {
        std::string bytes, message;
    };
    std::string version_1 = saved;  // the format before checksums
    version_1[8] = 1;
    const std::vector<Case> cases = {
        {saved.substr(0, saved.size() - 20),
         "damaged checkpoint (truncated: " + std::to_string(saved.size() - 20) +
             " bytes, its end missing)"},
        {"P6\n1 1\n255\nabc", "not a luz checkpoint"},
        {version_1,
         "checkpoint of version 1, this luz writes 2 (render again without it, or remove the "
         "file)"},
    };
    for (const Case& c : cases) {
        write_file(dir_ / "render.ckpt", c.bytes);
        const RunResult r = run_luz(checkpoint_render("out.png", "grid"), dir_);
        EXPECT_EQ(r.status, 2) << c.message;
        EXPECT_EQ(r.err, "render.ckpt: --checkpoint: " + c.message + "\n");
        EXPECT_EQ(read_file(dir_ / "render.ckpt"), c.bytes) << "left as it was";
        EXPECT_FALSE(std::filesystem::exists(dir_ / "out.png"));
    }
}

// A save cut by SIGKILL (mpirun kills a run one second after its SIGTERM) leaves a temporary
// file beside the checkpoint: the next run goes on from the checkpoint and removes it.
TEST_F(Checkpoint, ATemporaryFileOfAKilledSaveIsRemovedByTheNextRun) {
    ASSERT_EQ(run_and_interrupt(checkpoint_render("out.png", "grid"), dir_, 0), 130);
    const std::string saved = read_file(dir_ / "render.ckpt");
    const pid_t dead = fork();
    if (dead == 0) _exit(0);
    ASSERT_EQ(waitpid(dead, nullptr, 0), dead);
    const std::string cut = ".render.ckpt.tmp." + std::to_string(dead) + ".00ff00ff00ff00ff";
    write_file(dir_ / cut, saved.substr(0, saved.size() / 2));
    const RunResult r = run_luz(checkpoint_render("out.png", "grid"), dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(list_dir(dir_), (std::set<std::string>{"out.png", "stats.json"}));
}

}  // namespace
}  // namespace luz::test
