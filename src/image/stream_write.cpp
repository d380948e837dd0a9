// Streams as outputs: opened without blocking (a FIFO waits for its reader in 50 ms steps),
// written as the reader takes the bytes, with SIGPIPE held back so that EPIPE is an error.
#include "image/stream_write.h"

#include <fcntl.h>
#include <limits.h>
#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <system_error>
#include <thread>

#include "image/atomic_file.h"

namespace luz {
namespace {

constexpr int kStepMs = 50;

bool cancelled(const std::atomic<bool>* cancel) { return cancel && cancel->load(); }

/// SIGPIPE blocked for this thread while alive; one raised by a write of ours is taken back, so
/// that neither this process nor a handler of it sees it.
class SigpipeHeld {
  public:
    SigpipeHeld() {
        sigemptyset(&pipe_);
        sigaddset(&pipe_, SIGPIPE);
        sigset_t pending;
        sigemptyset(&pending);
        sigpending(&pending);
        was_pending_ = sigismember(&pending, SIGPIPE) == 1;
        pthread_sigmask(SIG_BLOCK, &pipe_, &old_);
    }
    ~SigpipeHeld() {
        if (!was_pending_) {
            const timespec now{0, 0};
            while (sigtimedwait(&pipe_, nullptr, &now) == SIGPIPE) {
            }
        }
        pthread_sigmask(SIG_SETMASK, &old_, nullptr);
    }
    SigpipeHeld(const SigpipeHeld&) = delete;
    SigpipeHeld& operator=(const SigpipeHeld&) = delete;

  private:
    sigset_t pipe_{}, old_{};
    bool was_pending_ = false;
};

/// Opens the stream for writing without blocking: a FIFO without a reader (ENXIO) is tried
/// again every 50 ms until it has one or `cancel` is set. Returns the descriptor or -errno.
int open_stream(const std::string& path, const std::atomic<bool>* cancel) {
    for (;;) {
        const int fd = ::open(path.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC | O_NONBLOCK);
        if (fd >= 0) return fd;
        if (errno == EINTR) continue;
        if (errno != ENXIO) return -errno;
        if (cancelled(cancel)) return -ECANCELED;
        std::this_thread::sleep_for(std::chrono::milliseconds(kStepMs));
    }
}

/// Writes all of `bytes` to `fd`, waiting (in 50 ms steps that check `cancel`) while it takes
/// no more. Pipes and sockets are written PIPE_BUF bytes at a time, so that a descriptor
/// left blocking never blocks once poll() said it takes more. Returns 0 or an errno value.
int write_all(int fd, std::string_view bytes, const std::atomic<bool>* cancel) {
    struct stat st {};
    const bool pipe = ::fstat(fd, &st) == 0 && (S_ISFIFO(st.st_mode) || S_ISSOCK(st.st_mode));
    const size_t chunk = pipe ? PIPE_BUF : size_t{1} << 20;
    while (!bytes.empty()) {
        if (cancelled(cancel)) return ECANCELED;
        pollfd p{fd, POLLOUT, 0};
        const int ready = ::poll(&p, 1, kStepMs);
        if (ready < 0 && errno != EINTR) return errno;
        if (ready <= 0) continue;
        const ssize_t n = ::write(fd, bytes.data(), std::min(chunk, bytes.size()));
        if (n < 0) {
            if (errno == EINTR || errno == EAGAIN) continue;
            return errno;
        }
        bytes.remove_prefix(static_cast<size_t>(n));
    }
    return 0;
}

}  // namespace

void write_stream(const OutputTarget& target, const std::string& label, std::string_view bytes,
                  const std::atomic<bool>* cancel) {
    SigpipeHeld held;
    int err = 0;
    if (target.kind == OutputTarget::Kind::descriptor) {
        if (target.fd == STDOUT_FILENO) std::fflush(stdout);  // what was printed comes first
        if (target.fd == STDERR_FILENO) std::fflush(stderr);
        err = ::fcntl(target.fd, F_GETFD) == -1 ? errno : write_all(target.fd, bytes, cancel);
        // Standard output's reader gone away (`| head -1`) stops what goes there, like any
        // printing; the other outputs are still written.
        if (err == EPIPE && target.fd == STDOUT_FILENO) err = 0;
    } else {
        const int fd = open_stream(target.path, cancel);
        if (fd < 0) {
            err = -fd;
        } else {
            err = write_all(fd, bytes, cancel);
            if (::close(fd) != 0 && err == 0 && errno != EINTR) err = errno;
        }
    }
    if (err == ECANCELED) throw WriteCancelled(label + ": cannot write: interrupted");
    if (err != 0)
        throw FileError(
            label + ": cannot write: " + std::error_code(err, std::generic_category()).message());
}

}  // namespace luz
