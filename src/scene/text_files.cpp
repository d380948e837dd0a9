// The loader's input files: regular files read with a size bound (see text_files.h).
#include "scene/text_files.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>

namespace luz {
namespace {

std::atomic<uint64_t> g_memory_limit{UINT64_MAX};

/// How much more than its size a file may turn out to hold (one being appended to while read);
/// beyond, it is not a file's contents (/proc/self/pagemap says 0 and holds gigabytes).
constexpr uint64_t kGrowthAllowed = uint64_t{1} << 20;

TextReader& source_slot() {
    static TextReader source;
    return source;
}

FileObserver& observer_slot() {
    static FileObserver observer;
    return observer;
}

/// Why a file of mode `mode` is not read, or nullptr for a regular file.
const char* not_regular(mode_t mode) {
    if (S_ISREG(mode)) return nullptr;
    if (S_ISDIR(mode)) return "is a directory";
    if (S_ISFIFO(mode)) return "not a regular file (a FIFO)";
    if (S_ISSOCK(mode)) return "not a regular file (a socket)";
    if (S_ISCHR(mode) || S_ISBLK(mode)) return "not a regular file (a device)";
    return "not a regular file";
}

/// Why a file of `size` bytes (unknown: more than the limit) is not read.
std::string too_large(std::optional<uint64_t> size) {
    const std::string limit =
        std::to_string(max_text_file_bytes()) +
        " bytes a scene, OBJ or MTL file may have (a quarter of --max-memory)";
    if (size) return "the file's " + std::to_string(*size) + " bytes are more than the " + limit;
    return "the file holds more than the " + limit;
}

/// Closes a file descriptor at the end of a scope.
struct FdCloser {
    int fd;
    ~FdCloser() { ::close(fd); }
};

}  // namespace

void set_memory_limit(uint64_t bytes) { g_memory_limit.store(bytes); }
uint64_t memory_limit() { return g_memory_limit.load(); }
uint64_t max_text_file_bytes() {
    const uint64_t limit = memory_limit();
    return limit == UINT64_MAX ? limit : limit / 4;
}

void set_file_source(TextReader source) { source_slot() = std::move(source); }
const TextReader& file_source() { return source_slot(); }

void set_file_observer(FileObserver observer) { observer_slot() = std::move(observer); }
const FileObserver& file_observer() { return observer_slot(); }

std::optional<std::string> read_text_file(const std::string& path, std::string& reason) {
    if (const TextReader& source = file_source()) return source(path, reason);
    std::optional<std::string> text = read_text_file_from_disk(path, reason);
    if (text && file_observer()) file_observer()(path, *text);
    return text;
}

std::optional<std::string> read_text_file_from_disk(const std::string& path, std::string& reason) {
    if (path.find('\0') != std::string::npos) {
        reason = "the path contains a NUL character";
        return std::nullopt;
    }
    // Before opening: a FIFO would block the open, a device could be endless (/dev/zero).
    struct stat st;
    if (::stat(path.c_str(), &st) != 0) {
        reason = std::strerror(errno);
        return std::nullopt;
    }
    if (const char* why = not_regular(st.st_mode)) {
        reason = why;
        return std::nullopt;
    }
    // O_NONBLOCK: should the path have become a FIFO since, the open does not wait for a writer.
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
    if (fd < 0) {
        reason = std::strerror(errno);
        return std::nullopt;
    }
    const FdCloser closer{fd};
    if (::fstat(fd, &st) != 0) {
        reason = std::strerror(errno);
        return std::nullopt;
    }
    if (const char* why = not_regular(st.st_mode)) {
        reason = why;
        return std::nullopt;
    }
    const uint64_t limit = max_text_file_bytes();
    const uint64_t size = st.st_size > 0 ? static_cast<uint64_t>(st.st_size) : 0;
    if (size > limit) {
        reason = too_large(size);
        return std::nullopt;
    }
    // The read stops at the limit, and soon after the size, whatever the size said: /proc files
    // say 0.
    std::string text;
    text.reserve(size);
    char buffer[1 << 16];
    for (;;) {
        const ssize_t n = ::read(fd, buffer, sizeof buffer);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) {
            reason = std::strerror(errno);
            return std::nullopt;
        }
        if (n == 0) break;
        if (static_cast<uint64_t>(n) > limit - text.size()) {
            reason = too_large(std::nullopt);
            return std::nullopt;
        }
        if (text.size() + static_cast<uint64_t>(n) > size + kGrowthAllowed) {
            reason = "the file holds more than its size (" + std::to_string(size) +
                     " bytes) says: a /proc file, or one being written";
            return std::nullopt;
        }
        text.append(buffer, static_cast<size_t>(n));
    }
    return text;
}

}  // namespace luz
