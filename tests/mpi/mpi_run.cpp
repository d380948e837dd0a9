// Test helpers for tests/mpi: mpirun in the foreground (run_program) or in the background
// (fork + exec), and the luz-mpi processes of a run read from /proc.
#include "mpi/mpi_run.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <sstream>
#include <thread>

namespace luz::test {

std::string mpi_skip_reason() {
#ifndef LUZ_HAVE_MPI
    return "luz-mpi was not built (no Open MPI found: install libopenmpi-dev and reconfigure)";
#else
    if (::access(LUZ_MPI_BINARY, X_OK) != 0) return "luz-mpi was not built: no " LUZ_MPI_BINARY;
    if (find_on_path("mpirun").empty()) return "mpirun is not on PATH (install openmpi-bin)";
    return "";
#endif
}

std::vector<std::string> mpirun_args(int np, const std::vector<std::string>& args) {
    std::vector<std::string> a = {"--allow-run-as-root", "--oversubscribe", "-np",
                                  std::to_string(np), LUZ_BINARY};
    a.insert(a.end(), args.begin(), args.end());
    return a;
}

RunResult run_mpirun(int np, const std::vector<std::string>& args,
                     const std::filesystem::path& cwd) {
    return run_program("mpirun", mpirun_args(np, args), cwd);
}

void MpiTest::SetUp() {
    TempDirTest::SetUp();
    const std::string reason = mpi_skip_reason();
    if (!reason.empty()) GTEST_SKIP() << reason;
}

Background start_mpirun(int np, const std::vector<std::string>& args,
                        const std::filesystem::path& cwd, const std::filesystem::path& err_path) {
    std::vector<std::string> all = mpirun_args(np, args);
    all.insert(all.begin(), "mpirun");
    std::vector<char*> argv;
    for (std::string& a : all) argv.push_back(a.data());
    argv.push_back(nullptr);
    Background b;
    b.err_path = err_path;
    b.pid = fork();
    if (b.pid == 0) {
        if (chdir(cwd.c_str()) != 0) _exit(126);
        const int null_fd = open("/dev/null", O_RDWR);
        const int err_fd = open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        dup2(null_fd, STDIN_FILENO);
        dup2(null_fd, STDOUT_FILENO);
        dup2(err_fd, STDERR_FILENO);
        execvp("mpirun", argv.data());
        _exit(127);
    }
    return b;
}

int wait_for_exit(pid_t pid, double seconds) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    for (;;) {
        int status = 0;
        const pid_t r = waitpid(pid, &status, WNOHANG);
        if (r == pid) return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
        if (r < 0 && errno != EINTR) return -1;
        if (std::chrono::steady_clock::now() >= end) return -1;
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
}

std::vector<pid_t> luz_mpi_processes(const std::filesystem::path& cwd) {
    std::error_code ec;
    const std::filesystem::path want = std::filesystem::weakly_canonical(cwd, ec);
    std::vector<pid_t> pids;
    for (const auto& e : std::filesystem::directory_iterator("/proc", ec)) {
        const std::string name = e.path().filename().string();
        if (name.empty() || !std::all_of(name.begin(), name.end(), ::isdigit)) continue;
        const std::string cmdline = read_file(e.path() / "cmdline");
        const std::string argv0 = cmdline.substr(0, cmdline.find('\0'));
        if (argv0.find("luz-mpi") == std::string::npos) continue;
        std::error_code link_ec;
        const std::filesystem::path where =
            std::filesystem::read_symlink(e.path() / "cwd", link_ec);
        if (link_ec || where != want) continue;
        // /proc/PID/stat: "PID (COMM) STATE …"; a zombie has ended.
        const std::string stat = read_file(e.path() / "stat");
        const size_t paren = stat.rfind(')');
        if (paren == std::string::npos || paren + 2 >= stat.size() || stat[paren + 2] == 'Z')
            continue;
        pids.push_back(static_cast<pid_t>(std::stol(name)));
    }
    std::sort(pids.begin(), pids.end());
    return pids;
}

int mpi_rank_of(pid_t pid) {
    const std::string env = read_file("/proc/" + std::to_string(pid) + "/environ");
    const std::string key = "OMPI_COMM_WORLD_RANK=";
    for (size_t at = 0; at < env.size();) {
        const size_t end = std::min(env.find('\0', at), env.size());
        const std::string_view var(env.data() + at, end - at);
        if (var.substr(0, key.size()) == key)
            return std::atoi(std::string(var.substr(key.size())).c_str());
        at = end + 1;
    }
    return -1;
}

double cpu_seconds(pid_t pid) {
    // "PID (COMM) STATE PPID …": utime and stime are the 12th and 13th fields after COMM.
    const std::string stat = read_file("/proc/" + std::to_string(pid) + "/stat");
    const size_t paren = stat.rfind(')');
    if (paren == std::string::npos) return 0.0;
    std::istringstream in(stat.substr(paren + 2));
    std::string field;
    unsigned long long utime = 0, stime = 0;
    for (int k = 1; k <= 13 && in >> field; ++k) {
        if (k == 12) utime = std::stoull(field);
        if (k == 13) stime = std::stoull(field);
    }
    return static_cast<double>(utime + stime) / static_cast<double>(::sysconf(_SC_CLK_TCK));
}

int count_lines_containing(const std::string& text, const std::string& needle) {
    std::istringstream in(text);
    int n = 0;
    for (std::string line; std::getline(in, line);)
        if (line.find(needle) != std::string::npos) ++n;
    return n;
}

}  // namespace luz::test
