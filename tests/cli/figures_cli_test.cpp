// `luz figures -o DIR` on bad input, failures and signals: exit status, one clear message, and
// nothing half-written left (no DIR, no temporary folder; an existing DIR untouched unless the
// run succeeded, and replaced only when luz figures made it). The figures program itself is
// replaced by small fake interpreters (LUZ_FIGURES_PYTHON) so these cases run in milliseconds;
// tests/figures/ runs the real one (and one case here interrupts it).
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <string>
#include <thread>

#include "cli/run_luz.h"
#include "cli/signal_luz.h"

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

/// Makes folder `dir` as luz figures does: with the marker file.
void make_figures_folder(const std::filesystem::path& dir) {
    std::filesystem::create_directory(dir);
    write_file(dir / ".luz-figures", "made by luz figures");
}

TEST_F(Figures, AFailedRunLeavesTheExistingFolderAsItWas) {
    make_figures_folder(dir_ / "figs");
    write_file(dir_ / "figs" / "old.txt", "old");
    // writes a file into --out (the last argument), then fails
    fake_python("py-fail", "for a; do out=$a; done; echo half > \"$out/index.html\"; exit 3");
    const RunResult r = run_luz({"figures", "-o", "figs"}, dir_);
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("left as it was"), std::string::npos) << r.err;
    EXPECT_EQ(entries(dir_), (std::set<std::string>{"figs"}));
    EXPECT_EQ(list_dir(dir_ / "figs"), (std::set<std::string>{".luz-figures", "old.txt"}));
}

// Writes index.html into --out (the last argument).
constexpr const char* kWritesPage =
    "for a; do out=$a; done; echo '<html></html>' > \"$out/index.html\"";

TEST_F(Figures, ASuccessfulRunReplacesAFolderItMadeWhole) {
    fake_python("py-ok", kWritesPage);
    const RunResult first = run_luz({"figures", "-o", "figs"}, dir_);
    EXPECT_EQ(first.status, 0) << first.err;
    EXPECT_EQ(list_dir(dir_ / "figs"), (std::set<std::string>{".luz-figures", "index.html"}));
    write_file(dir_ / "figs" / "old.txt", "old");
    const RunResult again = run_luz({"figures", "-o", "figs"}, dir_);
    EXPECT_EQ(again.status, 0) << again.err;
    EXPECT_EQ(entries(dir_), (std::set<std::string>{"figs"}));
    EXPECT_EQ(list_dir(dir_ / "figs"), (std::set<std::string>{".luz-figures", "index.html"}));
}

TEST_F(Figures, AnEmptyFolderIsFilled) {
    std::filesystem::create_directory(dir_ / "figs");
    fake_python("py-ok", kWritesPage);
    const RunResult r = run_luz({"figures", "-o", "figs"}, dir_);
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(list_dir(dir_ / "figs"), (std::set<std::string>{".luz-figures", "index.html"}));
}

TEST_F(Figures, AFolderLuzDidNotMakeExits2AndIsKeptWhole) {
    // The case: `-o precious` removed a thesis and its sources.
    std::filesystem::create_directories(dir_ / "precious" / "src");
    write_file(dir_ / "precious" / "thesis.tex", "\\documentclass{book}");
    write_file(dir_ / "precious" / "src" / "main.c", "int main() {}");
    std::filesystem::create_directory_symlink("precious", dir_ / "link");
    fake_python("py-ok", kWritesPage);
    for (const char* out : {"precious", "link", "precious/"}) {
        const RunResult r = run_luz({"figures", "-o", out}, dir_);
        EXPECT_EQ(r.status, 2) << out << ": " << r.err;
        EXPECT_EQ(count_lines(r.err), 1) << r.err;
        EXPECT_NE(r.err.find(std::string(out) + " exists and is not a luz figures folder"),
                  std::string::npos)
            << r.err;
        EXPECT_EQ(entries(dir_), (std::set<std::string>{"link", "precious"}));
        EXPECT_EQ(list_dir(dir_ / "precious"), (std::set<std::string>{"src", "thesis.tex"}));
        EXPECT_EQ(read_file(dir_ / "precious" / "thesis.tex"), "\\documentclass{book}");
        EXPECT_EQ(read_file(dir_ / "precious" / "src" / "main.c"), "int main() {}");
    }
}

TEST_F(Figures, AFolderMadeThroughASymbolicLinkReplacesItsTarget) {
    make_figures_folder(dir_ / "figs");
    std::filesystem::create_directory_symlink("figs", dir_ / "link");
    fake_python("py-ok", kWritesPage);
    const RunResult r = run_luz({"figures", "-o", "link"}, dir_);
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(std::filesystem::is_symlink(dir_ / "link"));
    EXPECT_EQ(entries(dir_), (std::set<std::string>{"figs", "link"}));
    EXPECT_EQ(list_dir(dir_ / "figs"), (std::set<std::string>{".luz-figures", "index.html"}));
}

TEST_F(Figures, SigtermEndsItWithinASecondWithOneLineAndNothingLeft) {
    make_figures_folder(dir_ / "figs");
    write_file(dir_ / "figs" / "old.txt", "old");
    // writes part of the page, then takes its time (a figure being rendered)
    fake_python("py-slow",
                "for a; do out=$a; done; echo half > \"$out/index.html\"; mkdir \"$out/work\"; "
                "exec sleep 5");
    const Signalled r = signal_luz({"figures", "-o", "figs"}, dir_, SIGTERM, [this] {
        for (const std::string& n : list_dir(dir_))
            if (n.rfind(".figs.tmp-", 0) == 0 && std::filesystem::exists(dir_ / n / "work"))
                return true;
        return false;
    });
    ASSERT_TRUE(r.sent) << r.err;
    EXPECT_EQ(r.status, 143) << r.err;
    EXPECT_LT(r.seconds, 1.0);
    EXPECT_EQ(r.err, "luz figures: interrupted\n");
    EXPECT_EQ(entries(dir_), (std::set<std::string>{"figs"}));
    EXPECT_EQ(list_dir(dir_ / "figs"), (std::set<std::string>{".luz-figures", "old.txt"}));
}

TEST_F(Figures, AProgramThatIgnoresSigtermIsKilledWithinASecond) {
    // ignores TERM, and so does what it starts (a render that would write on)
    fake_python("py-deaf",
                "for a; do out=$a; done; trap '' TERM; "
                "(sleep 0.7; echo late > \"$out/late.txt\") & mkdir \"$out/work\"; sleep 5");
    const Signalled r = signal_luz({"figures", "-o", "figs"}, dir_, SIGINT, [this] {
        for (const std::string& n : list_dir(dir_))
            if (n.rfind(".figs.tmp-", 0) == 0 && std::filesystem::exists(dir_ / n / "work"))
                return true;
        return false;
    });
    ASSERT_TRUE(r.sent) << r.err;
    EXPECT_EQ(r.status, 130) << r.err;
    EXPECT_LT(r.seconds, 1.0);
    EXPECT_EQ(r.err, "luz figures: interrupted\n");
    std::this_thread::sleep_for(std::chrono::milliseconds(800));  // the late write would be done
    EXPECT_TRUE(entries(dir_).empty()) << *entries(dir_).begin();
}

TEST_F(Figures, CtrlCEndsTheRealProgramQuietlyWithinASecond) {
    if (std::system("/usr/bin/python3 -c 'import matplotlib, numpy' 2>/dev/null") != 0)
        GTEST_SKIP() << "Debian's python3-matplotlib is not installed";
    // Ctrl-C on a terminal: SIGINT to the whole foreground job, once renders are under way.
    const Signalled r = signal_luz(
        {"figures", "-o", "figs"}, dir_, SIGINT,
        [this] {
            for (const std::string& n : list_dir(dir_))
                if (n.rfind(".figs.tmp-", 0) == 0 && std::filesystem::exists(dir_ / n / "work") &&
                    !list_dir(dir_ / n / "work").empty())
                    return true;
            return false;
        },
        60, /*to_group=*/true);
    ASSERT_TRUE(r.sent) << r.err;
    EXPECT_EQ(r.status, 130) << r.err;
    EXPECT_LT(r.seconds, 1.0);
    EXPECT_EQ(r.err.find("Traceback"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("KeyboardInterrupt"), std::string::npos) << r.err;
    ASSERT_GE(r.err.size(), 25u);
    EXPECT_EQ(r.err.substr(r.err.size() - 25), "luz figures: interrupted\n") << r.err;
    EXPECT_TRUE(entries(dir_).empty()) << *entries(dir_).begin();
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
