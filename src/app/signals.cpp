// SIGINT/SIGTERM handling for `luz render`: async-signal-safe handlers over lock-free atomics.
#include "app/signals.h"

#include <signal.h>
#include <unistd.h>

namespace luz {

namespace {

std::atomic<bool> g_interrupted{false};
std::atomic<int> g_signal{0};
std::atomic<bool> g_exit_now{false};
static_assert(std::atomic<bool>::is_always_lock_free && std::atomic<int>::is_always_lock_free,
              "signal handlers may only touch lock-free atomics");

/// Only async-signal-safe calls: atomics, write(), _exit().
extern "C" void on_signal(int sig) {
    const bool again = g_interrupted.exchange(true);
    int expected = 0;
    g_signal.compare_exchange_strong(expected, sig);
    if (again || g_exit_now.load()) {
        static const char message[] = "luz: interrupted\n";
        [[maybe_unused]] const ssize_t n = ::write(STDERR_FILENO, message, sizeof message - 1);
        ::_exit(128 + g_signal.load());
    }
}

}  // namespace

void install_stop_handler(void (*handler)(int)) {
    struct sigaction sa {};
    sa.sa_handler = handler;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART;
    sigaction(SIGINT, &sa, nullptr);
    sigaction(SIGTERM, &sa, nullptr);
}

void install_interrupt_handlers() { install_stop_handler(on_signal); }

void set_interrupt_exits_now(bool exit_now) {
    g_exit_now.store(exit_now);
    // a signal that came while the flag was only being set must not be lost
    if (exit_now && g_interrupted.load()) throw Interrupted{g_signal.load()};
}

const std::atomic<bool>& interrupt_flag() { return g_interrupted; }

int interrupt_signal() { return g_signal.load(); }

void throw_if_interrupted() {
    if (g_interrupted.load()) throw Interrupted{g_signal.load()};
}

}  // namespace luz
