// Output paths as found on disk: symlinks followed one by one (so that a regular file at their
// end is replaced, not the link), devices and FIFOs told apart, this process's descriptors named.
#include "image/output_target.h"

#include <fcntl.h>
#include <limits.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <system_error>

#include "image/atomic_file.h"

namespace luz {
namespace {

[[noreturn]] void fail(const std::string& path, int err) {
    throw FileError(path +
                    ": cannot write: " + std::error_code(err, std::generic_category()).message());
}

/// The folder of `p` as the kernel reads it ("." for a bare name); never normalised lexically,
/// so that ".." after a symlinked folder means what it means to the kernel.
std::string folder_of(const std::string& p) {
    const size_t slash = p.find_last_of('/');
    if (slash == std::string::npos) return ".";
    return slash == 0 ? "/" : p.substr(0, slash);
}

bool all_digits(const std::string& s) {
    return !s.empty() && s.find_first_not_of("0123456789") == std::string::npos;
}

/// The link `p` as an entry of /proc/PID/fd (or /proc/PID/task/TID/fd): its descriptor number
/// when PID is this process, -2 when it is another's, -1 when `p` is no such entry.
int descriptor_link(const std::string& p) {
    const std::string name = p.substr(p.find_last_of('/') + 1);
    if (!all_digits(name) || name.size() > 9) return -1;
    char* real = ::realpath(folder_of(p).c_str(), nullptr);
    if (!real) return -1;
    const std::string dir(real);
    std::free(real);
    if (dir.rfind("/proc/", 0) != 0 || dir.size() < 10 ||
        dir.compare(dir.size() - 3, 3, "/fd") != 0)
        return -1;
    std::string middle = dir.substr(6, dir.size() - 9);  // PID or PID/task/TID
    const size_t task = middle.find("/task/");
    if (task != std::string::npos) {
        if (!all_digits(middle.substr(task + 6))) return -1;
        middle.resize(task);
    }
    if (!all_digits(middle) || middle.size() > 9) return -1;
    if (std::stol(middle) != static_cast<long>(::getpid())) return -2;
    return std::stoi(name);
}

/// The target of the symlink `p`, as a path the kernel reads the same way.
std::string follow(const std::string& p, const std::string& label) {
    char buffer[PATH_MAX + 1];
    const ssize_t n = ::readlink(p.c_str(), buffer, PATH_MAX);
    if (n < 0) fail(label, errno);
    const std::string target(buffer, static_cast<size_t>(n));
    if (target.empty()) fail(label, ENOENT);
    if (target[0] == '/') return target;
    const size_t slash = p.find_last_of('/');
    return slash == std::string::npos ? target : p.substr(0, slash + 1) + target;
}

}  // namespace

OutputTarget resolve_output(const std::string& path) {
    OutputTarget t;
    std::string p = path;
    for (int hops = 0;; ++hops) {
        struct stat st {};
        if (::lstat(p.c_str(), &st) != 0) {
            if (errno != ENOENT) fail(path, errno);
            t.path = p;  // nothing there yet: a new file
            return t;
        }
        if (S_ISLNK(st.st_mode)) {
            const int fd = descriptor_link(p);
            if (fd >= 0) {
                t.kind = OutputTarget::Kind::descriptor;
                t.fd = fd;
                t.path = p;
                return t;
            }
            if (fd == -2) {  // another process's descriptor: opened like a device
                t.kind = OutputTarget::Kind::stream;
                t.path = p;
                return t;
            }
            if (hops >= 40) fail(path, ELOOP);
            p = follow(p, path);
            continue;
        }
        if (S_ISDIR(st.st_mode)) throw FileError(path + ": cannot write: is a folder");
        t.path = p;
        if (S_ISREG(st.st_mode)) {
            t.exists = true;
            t.mode = st.st_mode & 07777;
            t.uid = st.st_uid;
            t.gid = st.st_gid;
        } else {
            t.kind = OutputTarget::Kind::stream;
        }
        return t;
    }
}

FileIdentity file_identity(const std::string& path) {
    FileIdentity id;
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0) {
        id.exists = true;
        id.dev = st.st_dev;
        id.ino = st.st_ino;
        return id;
    }
    // Nothing there: the end of a dangling symlink's chain, in its folder's real path.
    std::string p = path;
    for (int hops = 0; hops < 40 && ::lstat(p.c_str(), &st) == 0 && S_ISLNK(st.st_mode); ++hops) {
        try {
            p = follow(p, path);
        } catch (const FileError&) {
            break;
        }
    }
    const std::string name = p.substr(p.find_last_of('/') + 1);
    if (char* real = ::realpath(folder_of(p).c_str(), nullptr)) {
        const std::string dir(real);
        std::free(real);
        id.path = (dir == "/" ? "" : dir) + "/" + name;
    } else {
        std::error_code ec;
        id.path = std::filesystem::absolute(p, ec).lexically_normal().string();
        if (ec) id.path = p;
    }
    return id;
}

}  // namespace luz
