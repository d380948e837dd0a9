// Standard output's errors: SIGPIPE caught (a no-op handler, reset by exec), EPIPE ignored,
// anything else (a full disk, a closed descriptor) reported once when the command ends.
#include "app/standard_output.h"

#include <signal.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>

#include "app/cli_main.h"

namespace luz {
namespace {

int g_error = 0;  ///< the first errno of a failed write to standard output

extern "C" void on_sigpipe(int) {}

}  // namespace

void catch_sigpipe() {
    struct sigaction sa {};
    sa.sa_handler = on_sigpipe;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART;
    sigaction(SIGPIPE, &sa, nullptr);
}

void flush_standard_output() {
    errno = 0;
    const bool failed = std::fflush(stdout) != 0 || std::ferror(stdout);
    if (failed && g_error == 0) g_error = errno != 0 ? errno : EIO;
}

int finish_standard_output(int status) {
    flush_standard_output();
    if (g_error == 0 || g_error == EPIPE) return status;
    print_error_line(std::string("luz: standard output: cannot write: ") + std::strerror(g_error));
    return status == 0 ? 1 : status;
}

}  // namespace luz
