// Input files that are not plain files (FIFOs, devices, /proc files that say 0 bytes and hold
// gigabytes) and files larger than the memory allows: refused at once, exit 2, one line.
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>

#include "cli/run_luz.h"

namespace luz::test {
namespace {

using Clock = std::chrono::steady_clock;

class InputFiles : public TempDirTest {
  protected:
    /// Runs luz; checks exit `status`, one line holding every fragment; returns seconds taken.
    double run(const std::vector<std::string>& args, int status,
               const std::vector<std::string>& fragments) {
        const auto start = Clock::now();
        const RunResult r = run_luz(args, dir_);
        const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
        EXPECT_EQ(r.status, status) << r.err;
        EXPECT_EQ(count_lines(r.err), 1) << r.err;
        for (const std::string& f : fragments) EXPECT_NE(r.err.find(f), std::string::npos) << r.err;
        EXPECT_EQ(r.err.find("std::"), std::string::npos) << r.err;
        return seconds;
    }

    /// A FIFO at `name` that a child process writes `text` into after `delay_ms` (so that a
    /// luz that waits for a writer ends, late, instead of hanging the test); reaped by TearDown.
    void make_late_fifo(const std::string& name, const std::string& text, int delay_ms) {
        const std::string path = (dir_ / name).string();
        ASSERT_EQ(mkfifo(path.c_str(), 0644), 0);
        writer_ = fork();
        if (writer_ == 0) {
            usleep(static_cast<useconds_t>(delay_ms) * 1000);
            const int fd = open(path.c_str(), O_WRONLY | O_NONBLOCK);
            if (fd >= 0) {
                (void)!write(fd, text.data(), text.size());
                close(fd);
            }
            _exit(0);
        }
    }

    void TearDown() override {
        if (writer_ > 0) {
            kill(writer_, SIGKILL);
            waitpid(writer_, nullptr, 0);
        }
        TempDirTest::TearDown();
    }

    pid_t writer_ = -1;
};

TEST_F(InputFiles, AFifoSceneIsRefusedAtOnce) {
    make_late_fifo("s.json", R"({"objects": [{"type": "sphere"}]})", 3000);
    EXPECT_LT(run({"render", "s.json", "-o", "out.png", "-q"}, 2,
                  {"s.json", "not a regular file (a FIFO)"}),
              1.0);
    EXPECT_FALSE(std::filesystem::exists(dir_ / "out.png"));
}

TEST_F(InputFiles, AFifoMeshIsRefusedAtOnce) {
    make_late_fifo("m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", 3000);
    write_file(dir_ / "s.json", R"({"objects": [{"type": "mesh", "file": "m.obj"}]})");
    EXPECT_LT(run({"render", "s.json", "-o", "out.png", "-q"}, 2,
                  {"s.json", "objects.0.file", "m.obj", "not a regular file (a FIFO)"}),
              1.0);
}

TEST_F(InputFiles, ADeviceSceneIsRefused) {
    // /dev/null reads as an empty file: what it is is said, not a JSON syntax error
    run({"render", "/dev/null", "-o", "out.png", "-q"}, 2,
        {"/dev/null: cannot read: not a regular file (a device)"});
    EXPECT_LT(run({"render", "/dev/zero", "-o", "out.png", "-q"}, 2,
                  {"/dev/zero: cannot read: not a regular file (a device)"}),
              1.0);
}

TEST_F(InputFiles, ProcFilesThatSayZeroBytesAreReadOnlyAsFarAsTheirSize) {
    // /proc/self/pagemap: a "regular file" of size 0 holding 8 bytes per page of address space
    EXPECT_LT(run({"render", "/proc/self/pagemap", "-o", "out.png", "-q"}, 2,
                  {"/proc/self/pagemap: cannot read: the file holds more than its size"}),
              1.0);
    write_file(dir_ / "s.json", R"({"objects": [{"type": "mesh", "file": "/proc/self/pagemap"}]})");
    EXPECT_LT(run({"render", "s.json", "-o", "out.png", "-q"}, 2,
                  {"s.json", "objects.0.file", "the file holds more than its size"}),
              1.0);
    // an MTL file that cannot be read is a warning: the mesh keeps the default material
    write_file(dir_ / "m.obj", "mtllib /proc/self/pagemap\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    write_file(dir_ / "s.json", R"({"image": {"width": 16, "height": 16},
                                    "objects": [{"type": "mesh", "file": "m.obj"}]})");
    EXPECT_LT(run({"render", "s.json", "-o", "out.png", "-q"}, 0,
                  {"luz: warning:", "m.obj:1:", "the file holds more than its size"}),
              1.0);
    EXPECT_TRUE(std::filesystem::exists(dir_ / "out.png"));
}

TEST_F(InputFiles, ASceneLargerThanAQuarterOfMaxMemoryIsRefused) {
    // 400 KB of spheres: fine by default, more than a quarter of 1 MB
    {
        std::ofstream s(dir_ / "s.json");
        s << R"({"objects": [)";
        for (int i = 0; i < 8000; ++i) {
            s << (i ? ",\n" : "") << R"({"type": "sphere", "center": [0, 0, )" << -i << "]}";
        }
        s << "]}";
    }
    run({"render", "s.json", "--max-memory", "1M", "-o", "out.png", "-q"}, 2,
        {"s.json: cannot read: the file's", "a quarter of --max-memory"});
    EXPECT_FALSE(std::filesystem::exists(dir_ / "out.png"));
}

}  // namespace
}  // namespace luz::test
