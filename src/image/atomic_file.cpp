// Atomic file writing: a temporary file in the same folder as the file a path names (flushed to
// disk on request), then renamed into place; streams written when committed.
#include "image/atomic_file.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/uio.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <climits>
#include <cstdio>
#include <filesystem>
#include <random>
#include <system_error>
#include <utility>

#include "image/stream_write.h"

namespace luz {

std::string error_text(int err) { return std::error_code(err, std::generic_category()).message(); }

namespace {

/// The folder part of `path` ("" or ending in '/') and its file name, the name cut to the
/// length a temporary name can hold under NAME_MAX.
std::pair<std::string, std::string> split_path(const std::string& path) {
    const size_t slash = path.find_last_of('/');
    const std::string dir = slash == std::string::npos ? "" : path.substr(0, slash + 1);
    std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
    if (name.size() > 100) name.resize(100);
    return {dir, name};
}

/// A 64-bit value that differs between calls and processes, for temporary file names.
uint64_t random_suffix() {
    static std::atomic<uint64_t> counter{0};
    static const uint64_t seed = [] {
        uint64_t s =
            static_cast<uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count());
        try {
            std::random_device rd;
            s ^= (static_cast<uint64_t>(rd()) << 32) ^ rd();
        } catch (...) {  // no entropy source: time and counter still make names unique enough
        }
        return s;
    }();
    // splitmix64 of seed + counter
    uint64_t z = seed + 0x9e3779b97f4a7c15ULL * (counter.fetch_add(1) + 1);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

/// Writes all of `pieces` to `fd`, one after the other, with as few system calls as the
/// kernel allows (writev, IOV_MAX pieces at a time); false with errno set on failure.
bool write_all(int fd, std::vector<std::string_view> pieces) {
    size_t first = 0;
    while (first < pieces.size()) {
        if (pieces[first].empty()) {
            ++first;
            continue;
        }
        iovec iov[IOV_MAX];
        int count = 0;
        for (size_t k = first; k < pieces.size() && count < IOV_MAX; ++k) {
            if (pieces[k].empty()) continue;
            iov[count].iov_base = const_cast<char*>(pieces[k].data());
            iov[count].iov_len = pieces[k].size();
            ++count;
        }
        ssize_t n = ::writev(fd, iov, count);
        if (n < 0) {
            if (errno == EINTR) continue;
            return false;
        }
        // Drop what was written: whole pieces, then the front of a partly written one.
        while (n > 0) {
            const size_t take = std::min(static_cast<size_t>(n), pieces[first].size());
            pieces[first].remove_prefix(take);
            n -= static_cast<ssize_t>(take);
            if (pieces[first].empty()) ++first;
        }
    }
    return true;
}

}  // namespace

PendingFile::PendingFile(std::string path, const std::string& bytes, Durability durability)
    : path_(std::move(path)), target_(resolve_output(path_)), durability_(durability) {
    if (is_stream()) {
        stream_bytes_ = bytes;
        return;
    }
    stage({bytes});
}

PendingFile::PendingFile(std::string path, std::string&& bytes, Durability durability)
    : path_(std::move(path)), target_(resolve_output(path_)), durability_(durability) {
    if (is_stream()) {
        stream_bytes_ = std::move(bytes);
        return;
    }
    stage({bytes});
}

PendingFile::PendingFile(std::string path, const std::vector<std::string_view>& pieces,
                         Durability durability)
    : path_(std::move(path)), target_(resolve_output(path_)), durability_(durability) {
    if (is_stream()) {
        for (std::string_view piece : pieces) stream_bytes_ += piece;
        return;
    }
    stage(pieces);
}

void PendingFile::stage(const std::vector<std::string_view>& pieces) {
    const auto [dir, name] = split_path(target_.path);  // beside the file its symlinks name
    const auto fail = [this](int err) {
        throw FileError(path_ + ": cannot write: " + error_text(err));
    };

    // Create the temporary file (0666 less the umask, as any new file).
    std::string tmp;
    int fd = -1;
    for (int attempt = 0; fd < 0; ++attempt) {
        char suffix[17];
        std::snprintf(suffix, sizeof suffix, "%016llx",
                      static_cast<unsigned long long>(random_suffix()));
        tmp = dir + "." + name + ".tmp." + std::to_string(::getpid()) + "." + suffix;
        fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd < 0 && (errno != EEXIST || attempt >= 100)) fail(errno);
    }
    // An existing file keeps its owner where this process may give it, then its mode.
    if (target_.exists) {
        struct stat st {};
        const bool other_owner =
            ::fstat(fd, &st) == 0 && (st.st_uid != target_.uid || st.st_gid != target_.gid);
        if (other_owner && ::fchown(fd, target_.uid, target_.gid) != 0) {
            // not allowed (not root): the new file is this user's, as any file it makes
        }
        ::fchmod(fd, target_.mode);
    }

    // Write, flush to disk if asked, close; any error removes the temporary file.
    int err = 0;
    if (!write_all(fd, pieces) || (durability_ == Durability::disk && ::fsync(fd) != 0))
        err = errno;
    if (::close(fd) != 0 && err == 0) err = errno;
    if (err != 0) {
        ::unlink(tmp.c_str());
        fail(err);
    }
    tmp_ = tmp;
}

PendingFile::~PendingFile() {
    if (!committed_ && !tmp_.empty()) ::unlink(tmp_.c_str());
}

void PendingFile::commit(const std::atomic<bool>* cancel) {
    if (committed_) return;
    if (is_stream()) {
        write_stream(target_, path_, stream_bytes_, cancel);
        committed_ = true;
        return;
    }
    if (::rename(tmp_.c_str(), target_.path.c_str()) != 0) {
        const int err = errno;
        ::unlink(tmp_.c_str());
        committed_ = true;  // nothing left to remove
        throw FileError(path_ + ": cannot write: " + error_text(err));
    }
    committed_ = true;
    if (durability_ != Durability::disk) return;
    // Best effort: make the rename itself durable.
    const size_t slash = target_.path.find_last_of('/');
    const std::string dir = slash == std::string::npos ? "." : target_.path.substr(0, slash + 1);
    const int dir_fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dir_fd >= 0) {
        ::fsync(dir_fd);
        ::close(dir_fd);
    }
}

void commit_together(const std::vector<PendingFile*>& files, const std::atomic<bool>* cancel) {
    for (PendingFile* f : files)
        if (f->is_stream()) f->commit(cancel);
    for (PendingFile* f : files) f->commit(cancel);
}

size_t remove_stale_temporaries(const std::string& path) {
    namespace fs = std::filesystem;
    OutputTarget target;
    try {
        target = resolve_output(path);
    } catch (const FileError&) {
        return 0;
    }
    if (target.kind != OutputTarget::Kind::file) return 0;
    const auto [dir, name] = split_path(target.path);
    const std::string prefix = "." + name + ".tmp.";
    size_t removed = 0;
    std::error_code ec;
    for (fs::directory_iterator it(dir.empty() ? "." : dir, ec), end; !ec && it != end;
         it.increment(ec)) {
        const std::string file = it->path().filename().string();
        if (file.compare(0, prefix.size(), prefix) != 0) continue;
        // <pid>.<16 hex digits>, as PendingFile names them
        const std::string rest = file.substr(prefix.size());
        const size_t dot = rest.find('.');
        if (dot == std::string::npos || dot == 0 || dot > 9 || rest.size() != dot + 17) continue;
        if (rest.find_first_not_of("0123456789") != dot) continue;
        if (rest.find_first_not_of("0123456789abcdef", dot + 1) != std::string::npos) continue;
        const pid_t pid = static_cast<pid_t>(std::stol(rest.substr(0, dot)));
        if (pid <= 0 || ::kill(pid, 0) == 0 || errno != ESRCH) continue;  // it may still write
        std::error_code remove_ec;
        if (it->is_regular_file(remove_ec) && fs::remove(it->path(), remove_ec)) ++removed;
    }
    return removed;
}

void write_file_atomically(const std::string& path, const std::string& bytes) {
    PendingFile file(path, bytes);
    file.commit();
}

}  // namespace luz
