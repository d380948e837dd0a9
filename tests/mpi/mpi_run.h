// Test helpers for tests/mpi: `mpirun -np N luz …` (docs/DISTRIBUTED.md) run like tests/cli runs
// luz, a fixture that skips when luz-mpi was not built or mpirun is missing, and the luz-mpi
// processes of a run found through /proc (for the tests that kill one or interrupt mpirun).
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <string>
#include <vector>

#include "cli/run_luz.h"

namespace luz::test {

/// Why the tests cannot run here ("" when they can): no luz-mpi built, or no mpirun on PATH.
std::string mpi_skip_reason();

/// The command line of `mpirun --allow-run-as-root --oversubscribe -np N LUZ_BINARY args…`
/// (root in CI; more processes than cores), without the program name.
std::vector<std::string> mpirun_args(int np, const std::vector<std::string>& args);

/// Runs `mpirun -np np luz args…` in `cwd` and waits for it (run_program).
RunResult run_mpirun(int np, const std::vector<std::string>& args,
                     const std::filesystem::path& cwd);

/// A TempDirTest that skips (GTEST_SKIP, with the reason) where mpirun -np N luz cannot run.
class MpiTest : public TempDirTest {
  protected:
    void SetUp() override;
};

/// An mpirun started in the background: stdin and stdout /dev/null, stderr into `err_path`.
struct Background {
    pid_t pid = -1;
    std::filesystem::path err_path;
};
Background start_mpirun(int np, const std::vector<std::string>& args,
                        const std::filesystem::path& cwd, const std::filesystem::path& err_path);

/// Waits up to `seconds` for `pid` (a child) to exit: its status (128 + signal when killed), or
/// -1 when it still runs.
int wait_for_exit(pid_t pid, double seconds);

/// The live luz-mpi processes working in folder `cwd` (cmdline names luz-mpi, /proc/PID/cwd is
/// `cwd`, not a zombie).
std::vector<pid_t> luz_mpi_processes(const std::filesystem::path& cwd);

/// OMPI_COMM_WORLD_RANK of process `pid` (from /proc/PID/environ), or -1.
int mpi_rank_of(pid_t pid);

/// CPU seconds (user + system) process `pid` has used so far (/proc/PID/stat), or 0.
double cpu_seconds(pid_t pid);

/// Number of lines of `text` that contain `needle`.
int count_lines_containing(const std::string& text, const std::string& needle);

}  // namespace luz::test
