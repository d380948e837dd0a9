// Test helpers for tests/cli: run the real `luz` binary (or another program, e.g. mpirun) in a
// folder and capture what it says, and a fixture giving each test its own temporary folder.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "sanitizer.h"  // kSlowdown

namespace luz::test {

struct RunResult {
    int status = -1;  ///< exit status, or 128 + signal when killed
    std::string out;  ///< standard output
    std::string err;  ///< standard error
};

/// Runs LUZ_BINARY with `args` in folder `cwd`, stdin from /dev/null, stdout and stderr
/// captured through pipes (so neither is a terminal).
RunResult run_luz(const std::vector<std::string>& args, const std::filesystem::path& cwd);

/// Runs any program the same way: `program` is a path, or a name looked up on PATH (mpirun).
RunResult run_program(const std::string& program, const std::vector<std::string>& args,
                      const std::filesystem::path& cwd);

/// The path of `name` on PATH (an executable file), or "" when there is none.
std::string find_on_path(const std::string& name);

/// The same with standard input, output and error on a pseudo-terminal; `out` gets everything.
RunResult run_luz_on_terminal(const std::vector<std::string>& args,
                              const std::filesystem::path& cwd);

std::string read_file(const std::filesystem::path& p);
void write_file(const std::filesystem::path& p, const std::string& content);

/// The names of the entries of folder `dir`.
std::set<std::string> list_dir(const std::filesystem::path& dir);

/// Number of '\n' in `s`.
int count_lines(const std::string& s);

/// Each test in its own temporary folder, removed afterwards.
class TempDirTest : public testing::Test {
  protected:
    void SetUp() override;
    void TearDown() override;
    std::filesystem::path dir_;
};

}  // namespace luz::test
