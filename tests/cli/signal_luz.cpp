// signal_luz(): fork, exec, poll, signal, wait, time.
#include "cli/signal_luz.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <thread>

namespace luz::test {

namespace {
using Clock = std::chrono::steady_clock;

double since(Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
}

int exit_status(int status) {
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}
}  // namespace

Signalled signal_luz(const std::vector<std::string>& args, const std::filesystem::path& cwd,
                     int sig, const std::function<bool()>& ready, double wait_at_most,
                     bool to_group) {
    std::string binary = LUZ_BINARY;
    std::vector<char*> argv{binary.data()};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    const std::filesystem::path err_path = cwd.parent_path() / (cwd.filename().string() + ".err");
    const pid_t pid = fork();
    if (pid == 0) {
        setpgid(0, 0);
        if (chdir(cwd.c_str()) != 0) _exit(126);
        const int null_fd = open("/dev/null", O_RDWR);
        const int err_fd = open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        dup2(null_fd, STDIN_FILENO);
        dup2(null_fd, STDOUT_FILENO);
        dup2(err_fd, STDERR_FILENO);
        execv(binary.c_str(), argv.data());
        _exit(127);
    }
    setpgid(pid, pid);
    Signalled r;
    const auto start = Clock::now();
    int status = 0;
    bool ended = false;
    while (!ended && since(start) < wait_at_most && !ready()) {
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
        ended = waitpid(pid, &status, WNOHANG) == pid;
    }
    Clock::time_point sent = Clock::now();
    if (!ended) {
        r.sent = since(start) < wait_at_most;
        sent = Clock::now();
        if (r.sent) {
            kill(to_group ? -pid : pid, sig);
        } else {
            kill(-pid, SIGKILL);  // the wait ran out: luz and what it started go
        }
        while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
        }
    }
    r.seconds = since(sent);
    r.status = exit_status(status);
    r.err = read_file(err_path);
    std::filesystem::remove(err_path);
    return r;
}

std::function<bool()> after_seconds(double seconds) {
    const auto start = Clock::now();
    return [start, seconds] { return since(start) >= seconds; };
}

bool has_entry_containing(const std::filesystem::path& dir, const std::string& part) {
    std::error_code ec;
    for (std::filesystem::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        if (it->path().filename().string().find(part) != std::string::npos) return true;
    }
    return false;
}

}  // namespace luz::test
