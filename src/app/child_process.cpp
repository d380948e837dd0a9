// run_child(): fork and exec into a process group of its own, forward SIGINT/SIGTERM to the
// group, and wait until every process of it has ended.
#include "app/child_process.h"

#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>

namespace luz {
namespace {

std::atomic<int> g_stop{0};
static_assert(std::atomic<int>::is_always_lock_free,
              "signal handlers may only touch lock-free atomics");

/// Only an atomic store: the waiting loop does the rest.
extern "C" void on_stop(int sig) {
    int expected = 0;
    g_stop.compare_exchange_strong(expected, sig);
}

/// Grace between the group's SIGTERM and its SIGKILL.
constexpr std::chrono::milliseconds kGrace{500};
/// How often the waiting loop looks at the children and the flag.
constexpr long kPollNanoseconds = 10'000'000;

}  // namespace

int stop_signal() { return g_stop.load(); }

ChildResult run_child(const std::vector<std::string>& argv) {
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);

    struct sigaction sa {};
    sa.sa_handler = on_stop;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, nullptr);
    sigaction(SIGTERM, &sa, nullptr);
    // Orphans of the child (a render python3 started) become ours, so that we can wait for them.
    prctl(PR_SET_CHILD_SUBREAPER, 1);

    const pid_t pid = fork();
    if (pid == 0) {
        setpgid(0, 0);
        prctl(PR_SET_PDEATHSIG, SIGKILL);  // should this process die first
        signal(SIGINT, SIG_DFL);
        signal(SIGTERM, SIG_DFL);
        execv(args[0], args.data());
        _exit(127);
    }
    ChildResult result;
    if (pid < 0) return result;
    setpgid(pid, pid);  // also here: no signal may reach the group before it exists

    using Clock = std::chrono::steady_clock;
    bool child_done = false;
    Clock::time_point term_sent{};
    bool term = false, kill_sent = false;
    for (;;) {
        int status = 0;
        const pid_t w = waitpid(-1, &status, WNOHANG);
        if (w == pid) {
            child_done = true;
            result.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
            continue;
        }
        if (w > 0) continue;                  // an adopted process ended
        if (w < 0 && errno == ECHILD) break;  // every process of the group has ended
        if (w < 0 && errno != EINTR) break;
        if (child_done && g_stop.load() == 0) break;  // a normal end: nothing left to stop
        if (g_stop.load() != 0 && !term) {
            kill(-pid, SIGTERM);
            term = true;
            term_sent = Clock::now();
        }
        if (term && !kill_sent && Clock::now() - term_sent > kGrace) {
            kill(-pid, SIGKILL);
            kill_sent = true;
        }
        const timespec pause{0, kPollNanoseconds};
        nanosleep(&pause, nullptr);
    }
    result.stopped = g_stop.load();
    return result;
}

}  // namespace luz
