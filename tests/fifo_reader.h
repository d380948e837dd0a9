// FifoReader: a test's reader of a FIFO that never hangs, for the tests of outputs that are
// FIFOs (tests/cli/output_safety_test.cpp, tests/image/output_kinds_test.cpp).
#pragma once

#include <fcntl.h>
#include <poll.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <string>
#include <thread>

namespace luz {

/// Reads a FIFO in a thread without ever hanging: opened without blocking (so that the writer
/// finds a reader), read as data comes, ended by the writer closing it or, once `done` is set,
/// by 200 ms without data (a writer that replaced the FIFO instead never comes).
class FifoReader {
  public:
    explicit FifoReader(const std::string& path)
        : fd_(::open(path.c_str(), O_RDONLY | O_NONBLOCK)), thread_([this] { run(); }) {}
    ~FifoReader() { finish(); }
    /// Waits for the end; what was read.
    const std::string& finish() {
        done_.store(true);
        if (thread_.joinable()) thread_.join();
        if (fd_ >= 0) ::close(fd_);
        fd_ = -1;
        return got_;
    }

  private:
    void run() {
        for (int idle = 0; fd_ >= 0 && idle < 2;) {
            pollfd p{fd_, POLLIN, 0};
            if (::poll(&p, 1, 100) <= 0) {  // no writer yet, or none coming
                if (done_.load()) ++idle;
                continue;
            }
            char buffer[4096];
            const ssize_t n = ::read(fd_, buffer, sizeof buffer);
            if (n <= 0 && (n == 0 || errno != EAGAIN)) return;  // the writer closed it
            if (n > 0) got_.append(buffer, static_cast<size_t>(n));
        }
    }
    int fd_;
    std::string got_;
    std::atomic<bool> done_{false};
    std::thread thread_;
};

}  // namespace luz
