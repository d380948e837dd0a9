// Under mpirun (docs/DISTRIBUTED.md): bad input exits 2 with luz's one message (whatever the number
// of processes), commands other than render run as usual, and the ordinary luz does not link MPI.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "mpi/mpi_run.h"

namespace luz::test {
namespace {

namespace fs = std::filesystem;

/// Standard error without mpirun's own boxed notices (a line of dashes, the notice, a line of
/// dashes: "Primary job terminated normally, but 1 process returned a non-zero exit code…",
/// "mpirun detected that one or more processes exited with non-zero status…"): what luz said.
std::string without_mpirun_notices(const std::string& err) {
    std::istringstream in(err);
    std::string kept;
    bool in_box = false;
    for (std::string line; std::getline(in, line);) {
        if (line.size() >= 20 && line.find_first_not_of('-') == std::string::npos) {
            in_box = !in_box;
            continue;
        }
        if (!in_box) kept += line + "\n";
    }
    return kept;
}

struct BadCase {
    const char* name;
    std::vector<std::string> args;
    const char* needle;  ///< the file or option luz's message names
    const char* file;    ///< a file to write first (or nullptr)
    const char* file_content;
};

class BadInputMpi : public MpiTest {};

TEST_F(BadInputMpi, Exit2WithLuzsOneMessageAndNoFile) {
    const BadCase cases[] = {
        {"missing scene",
         {"render", "missing.json", "-o", "x.png"},
         "missing.json",
         nullptr,
         nullptr},
        {"bad --width",
         {"render", "demo:whitted", "--width", "0", "-o", "x.png"},
         "--width",
         nullptr,
         nullptr},
        {"malformed JSON",
         {"render", "bad.json", "-o", "x.png"},
         "bad.json",
         "bad.json",
         "{\"image\": {\"width\": 64,\n"},
        {"unknown option",
         {"render", "demo:whitted", "--frobnicate", "-o", "x.png"},
         "--frobnicate",
         nullptr,
         nullptr},
    };
    for (const BadCase& c : cases) {
        SCOPED_TRACE(c.name);
        const fs::path one = dir_ / "one", many = dir_ / "many";
        fs::remove_all(one);
        fs::remove_all(many);
        fs::create_directory(one);
        fs::create_directory(many);
        std::set<std::string> inputs;
        if (c.file) {
            write_file(one / c.file, c.file_content);
            write_file(many / c.file, c.file_content);
            inputs.insert(c.file);
        }
        const RunResult r1 = run_luz(c.args, one);
        ASSERT_EQ(r1.status, 2) << r1.err;
        ASSERT_EQ(count_lines_containing(r1.err, c.needle), 1) << r1.err;

        const RunResult r = run_mpirun(3, c.args, many);
        EXPECT_EQ(r.status, 2) << r.err;
        // Once, not once per process; mpirun's own notices do not name the file or option.
        EXPECT_EQ(count_lines_containing(r.err, c.needle), 1) << r.err;
        // And luz said nothing else (no "luz: interrupted" from a process mpirun ended).
        EXPECT_EQ(without_mpirun_notices(r.err), r1.err) << r.err;
        EXPECT_EQ(list_dir(many), inputs);
    }
}

class CommandsMpi : public MpiTest {};

TEST_F(CommandsMpi, ScenesRunsInEveryProcessAsUsual) {
    // Not exec'd into luz-mpi: each of the 2 processes lists the scenes.
    const RunResult r = run_program("mpirun", mpirun_args(2, {"scenes"}), dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(count_lines_containing(r.out, "demo:whitted"), 2) << r.out;
    EXPECT_EQ(r.err, "");
}

TEST_F(CommandsMpi, ThreadsBeyondTheBindingAreWarnedOf) {
    // Open MPI binds a process of -np 1 to one core: --threads 2 there shares it, and luz says
    // so (docs/DISTRIBUTED.md#threads); --bind-to none gives it every core, and no warning.
    const std::vector<std::string> render = {"render",   "demo:whitted", "--width",   "32",
                                             "--height", "24",           "--threads", "2",
                                             "-q",       "-o",           "x.png"};
    const RunResult bound = run_program("mpirun", mpirun_args(1, render), dir_);
    ASSERT_EQ(bound.status, 0) << bound.err;
    EXPECT_EQ(count_lines_containing(bound.err, "luz: warning: --threads 2, but mpirun bound"), 1)
        << bound.err;
    std::vector<std::string> unbound = mpirun_args(1, render);
    unbound.insert(unbound.begin(), "--bind-to");
    unbound.insert(unbound.begin() + 1, "none");
    const RunResult free = run_program("mpirun", unbound, dir_);
    ASSERT_EQ(free.status, 0) << free.err;
    if (std::thread::hardware_concurrency() >= 2) {
        EXPECT_EQ(free.err, "");
    }
}

// Not an MpiTest: it holds wherever luz is built, with or without Open MPI.
class LuzLinks : public TempDirTest {};

TEST_F(LuzLinks, OrdinaryLuzDoesNotLinkMpi) {
    const RunResult r = run_program("ldd", {LUZ_BINARY}, dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("libc.so"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("libmpi"), std::string::npos) << r.out;
#ifdef LUZ_HAVE_MPI
    // The check can see MPI where it is linked.
    const RunResult m = run_program("ldd", {LUZ_MPI_BINARY}, dir_);
    ASSERT_EQ(m.status, 0) << m.err;
    EXPECT_NE(m.out.find("libmpi"), std::string::npos) << m.out;
#endif
}

}  // namespace
}  // namespace luz::test
