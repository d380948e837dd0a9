// `luz figures -o DIR` on bad input and failures: exit status, one clear message, and nothing
// half-written left (no DIR, no temporary folder; an existing DIR untouched unless the run
// succeeded). The figures program itself is replaced by small fake interpreters
// (LUZ_FIGURES_PYTHON) so these cases run in milliseconds; tests/figures/ runs the real one.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <string>

#include "cli/run_luz.h"

namespace luz::test {
namespace {

class Figures : public TempDirTest {
  protected:
    void TearDown() override {
        ::unsetenv("LUZ_FIGURES_PYTHON");
        TempDirTest::TearDown();
    }
    /// Writes an executable shell script `name` and makes luz figures run it as python3.
    void fake_python(const std::string& name, const std::string& body) {
        const std::filesystem::path p = dir_ / name;
        write_file(p, "#!/bin/sh\n" + body + "\n");
        ::chmod(p.c_str(), 0755);
        ::setenv("LUZ_FIGURES_PYTHON", p.c_str(), 1);
    }
};

/// The folder's entries apart from the fake interpreters (named py*).
std::set<std::string> entries(const std::filesystem::path& dir) {
    std::set<std::string> out;
    for (const std::string& n : list_dir(dir))
        if (n.rfind("py", 0) != 0) out.insert(n);
    return out;
}

TEST_F(Figures, OntoAnExistingFileExits2NamingItAndKeepsTheFile) {
    write_file(dir_ / "f", "keep");
    const RunResult r = run_luz({"figures", "-o", "f"}, dir_);
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("-o f"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("not a folder"), std::string::npos) << r.err;
    EXPECT_EQ(read_file(dir_ / "f"), "keep");
    EXPECT_EQ(entries(dir_), (std::set<std::string>{"f"}));
}

TEST_F(Figures, IntoAMissingFolderExits2NamingIt) {
    const RunResult r = run_luz({"figures", "-o", "nowhere/figs"}, dir_);
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("nowhere"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("does not exist"), std::string::npos) << r.err;
    EXPECT_TRUE(entries(dir_).empty());
}

TEST_F(Figures, IntoAnUnwritablePlaceExits1WithAClearMessage) {
    // /proc refuses new folders even to root (a read-only folder would not stop root)
    const RunResult r = run_luz({"figures", "-o", "/proc/luz-figures-test"}, dir_);
    EXPECT_EQ(r.status, 1);
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("/proc"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists("/proc/luz-figures-test"));
}

TEST_F(Figures, IntoAReadOnlyFolderExits1AndWritesNothing) {
    if (::geteuid() == 0) GTEST_SKIP() << "root writes into read-only folders";
    std::filesystem::create_directory(dir_ / "ro");
    ::chmod((dir_ / "ro").c_str(), 0555);
    const RunResult r = run_luz({"figures", "-o", "ro/figs"}, dir_);
    ::chmod((dir_ / "ro").c_str(), 0755);
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("cannot write"), std::string::npos) << r.err;
    EXPECT_TRUE(list_dir(dir_ / "ro").empty());
}

TEST_F(Figures, WithoutPython3Exits1NamingTheDebianPackage) {
    ::setenv("LUZ_FIGURES_PYTHON", (dir_ / "no-such-python3").c_str(), 1);
    const RunResult r = run_luz({"figures", "-o", "figs"}, dir_);
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("python3-matplotlib"), std::string::npos) << r.err;
    EXPECT_TRUE(entries(dir_).empty());
}

TEST_F(Figures, WithoutMatplotlibExits1NamingTheDebianPackageAndLeavesNothing) {
    // Debian's python3 without its dist-packages (-S): numpy and matplotlib cannot be imported
    fake_python("py-no-site", "exec /usr/bin/python3 -S \"$@\"");
    const RunResult r = run_luz({"figures", "-o", "figs"}, dir_);
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("python3-matplotlib"), std::string::npos) << r.err;
    EXPECT_TRUE(entries(dir_).empty()) << "left: " << *list_dir(dir_).begin();
}

TEST_F(Figures, AFailedRunLeavesTheExistingFolderAsItWas) {
    std::filesystem::create_directory(dir_ / "figs");
    write_file(dir_ / "figs" / "old.txt", "old");
    // writes a file into --out (the last argument), then fails
    fake_python("py-fail", "for a; do out=$a; done; echo half > \"$out/index.html\"; exit 3");
    const RunResult r = run_luz({"figures", "-o", "figs"}, dir_);
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("left as it was"), std::string::npos) << r.err;
    EXPECT_EQ(entries(dir_), (std::set<std::string>{"figs"}));
    EXPECT_EQ(list_dir(dir_ / "figs"), (std::set<std::string>{"old.txt"}));
}

TEST_F(Figures, ASuccessfulRunReplacesTheFolderWhole) {
    std::filesystem::create_directory(dir_ / "figs");
    write_file(dir_ / "figs" / "old.txt", "old");
    fake_python("py-ok", "for a; do out=$a; done; echo '<html></html>' > \"$out/index.html\"");
    const RunResult r = run_luz({"figures", "-o", "figs"}, dir_);
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(entries(dir_), (std::set<std::string>{"figs"}));
    EXPECT_EQ(list_dir(dir_ / "figs"), (std::set<std::string>{"index.html"}));
}

TEST_F(Figures, TheProgramGetsThisBinaryItsScenesAndATemporaryFolderBesideDir) {
    fake_python("py-args", "echo \"$@\" > \"$LUZ_ARGS_FILE\"; exit 1");
    ::setenv("LUZ_ARGS_FILE", (dir_ / "args.txt").c_str(), 1);
    const RunResult r = run_luz({"figures", "-o", "figs"}, dir_);
    ::unsetenv("LUZ_ARGS_FILE");
    EXPECT_EQ(r.status, 1);
    const std::string args = read_file(dir_ / "args.txt");
    EXPECT_NE(args.find("luz_figures.py --luz "), std::string::npos) << args;
    EXPECT_NE(args.find(std::filesystem::canonical(LUZ_BINARY).string()), std::string::npos)
        << args;
    EXPECT_NE(args.find("--scenes "), std::string::npos) << args;
    EXPECT_NE(args.find("--out " + std::filesystem::canonical(dir_).string() + "/.figs.tmp-"),
              std::string::npos)
        << args;
}

}  // namespace
}  // namespace luz::test
