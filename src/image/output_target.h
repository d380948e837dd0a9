// What an output path names, so that writing it never destroys anything but the output's own
// previous version: a regular file (through its symlinks) to replace, or a stream to write to.
#pragma once

#include <sys/types.h>

#include <string>

namespace luz {

/// An output path as found on disk, before anything is written.
struct OutputTarget {
    enum class Kind {
        file,        ///< a regular file, or none yet: written beside it and renamed onto it
        stream,      ///< a device, FIFO or socket: opened and written to, never replaced
        descriptor,  ///< one of this process's open descriptors (/dev/stdout, /dev/fd/N)
    };
    Kind kind = Kind::file;
    /// file: the path renamed onto — the end of the path's symlinks (they are written
    /// through); stream: the path to open.
    std::string path;
    int fd = -1;          ///< descriptor: its number
    bool exists = false;  ///< file: a regular file is there (its mode and owner are kept)
    mode_t mode = 0;
    uid_t uid = 0;
    gid_t gid = 0;
};

/// Where writing `path` goes (follows symlinks one by one, at most 40). Throws FileError
/// ("PATH: cannot write: is a folder", "…: Too many levels of symbolic links", …) for a
/// folder or a path that cannot be looked up; a missing folder is found when writing.
OutputTarget resolve_output(const std::string& path);

/// The same file, as far as the disk can tell before writing: the device and inode of what
/// `path` names (through its symlinks), or, when nothing is there yet, the absolute path it
/// would be created at with its folders' symlinks resolved.
struct FileIdentity {
    bool exists = false;
    dev_t dev = 0;
    ino_t ino = 0;
    std::string path;  ///< resolved path (when it does not exist)

    bool operator==(const FileIdentity&) const = default;
    auto operator<=>(const FileIdentity&) const = default;
};

/// The identity of `path` (never throws: what cannot be resolved keeps its absolute path).
FileIdentity file_identity(const std::string& path);

}  // namespace luz
