// `mpirun -np N luz render x.nff` (docs/SCENES.md#nff, §3.1): an NFF scene, read by rank 0 and sent
// to the others, gives the same bytes as in one process, and bad NFF is luz's one FILE:LINE
// message.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "mpi/mpi_run.h"

namespace luz::test {
namespace {

namespace fs = std::filesystem;

class NffMpi : public MpiTest {};

TEST_F(NffMpi, SameBytesAsOneProcess) {
    const fs::path scene = fs::path(LUZ_SOURCE_DIR) / "tests" / "scenes" / "nff" / "small.nff";
    const std::vector<std::string> args = {"render",   scene.string(), "-o", "x.pfm",
                                           "--aov",    "depth",        "-q", "--aa",
                                           "adaptive", "--threads",    "1"};
    fs::create_directory(dir_ / "one");
    fs::create_directory(dir_ / "many");
    const RunResult one = run_luz(args, dir_ / "one");
    ASSERT_EQ(one.status, 0) << one.err;
    const RunResult many = run_mpirun(2, args, dir_ / "many");
    ASSERT_EQ(many.status, 0) << many.err;
    for (const char* f : {"x.pfm", "x.depth.pfm"}) {
        const std::string a = read_file(dir_ / "one" / f);
        EXPECT_FALSE(a.empty()) << f;
        EXPECT_TRUE(a == read_file(dir_ / "many" / f)) << f;
    }
}

TEST_F(NffMpi, BadNffIsOneMessageAndNoFile) {
    write_file(dir_ / "bad.nff", "b 0 0 0\nl 1 2 3\n");
    const RunResult r = run_mpirun(2, {"render", "bad.nff", "-o", "x.png"}, dir_);
    EXPECT_EQ(r.status, 2);
    // once (rank 0 says it; mpirun's own notices follow)
    const std::string message = "bad.nff:2: l: before \"v\" (the viewpoint must come first";
    const size_t at = r.err.find(message);
    EXPECT_NE(at, std::string::npos) << r.err;
    EXPECT_EQ(r.err.find(message, at + 1), std::string::npos) << r.err;
    EXPECT_EQ(list_dir(dir_), std::set<std::string>{"bad.nff"});
}

}  // namespace
}  // namespace luz::test
