// `luz web [-o DIR]` (docs/WEB.md): writes DIR/luz.html, the very page web/ built; bad folders exit
// 2 with one line naming them; a luz built without Emscripten says how to get the page.
#include <gtest/gtest.h>

#include <string>

#include "cli/run_luz.h"

namespace luz::test {
namespace {

using Web = TempDirTest;

#ifdef LUZ_WEB_HTML  // this build made the page (tests/CMakeLists.txt)

TEST_F(Web, WritesTheBuiltPageIntoANewFolder) {
    const RunResult r = run_luz({"web", "-o", "page"}, dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_EQ(list_dir(dir_ / "page"), (std::set<std::string>{"luz.html"}));
    const std::string page = read_file(dir_ / "page" / "luz.html");
    EXPECT_EQ(page, read_file(LUZ_WEB_HTML));
    EXPECT_EQ(page.rfind("<!DOCTYPE html>", 0), 0u);
}

TEST_F(Web, WritesIntoTheCurrentFolderByDefault) {
    const RunResult r = run_luz({"web"}, dir_);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(list_dir(dir_), (std::set<std::string>{"luz.html"}));
}

TEST_F(Web, OntoAFileExits2NamingItAndKeepsTheFile) {
    write_file(dir_ / "f", "keep");
    const RunResult r = run_luz({"web", "-o", "f"}, dir_);
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("-o f: exists and is not a folder"), std::string::npos) << r.err;
    EXPECT_EQ(read_file(dir_ / "f"), "keep");
    EXPECT_EQ(list_dir(dir_), (std::set<std::string>{"f"}));
}

TEST_F(Web, IntoAMissingFolderExits2NamingIt) {
    const RunResult r = run_luz({"web", "-o", "nowhere/page"}, dir_);
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("nowhere"), std::string::npos) << r.err;
    EXPECT_TRUE(list_dir(dir_).empty());
}

#else

TEST_F(Web, WithoutThePageExits2SayingHowToBuildIt) {
    const RunResult r = run_luz({"web", "-o", "page"}, dir_);
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("apt-get install emscripten"), std::string::npos) << r.err;
    EXPECT_TRUE(list_dir(dir_).empty());
}

#endif

}  // namespace
}  // namespace luz::test
