// Files written atomically: under a temporary name in the same folder, then renamed into place,
// so a failure never leaves a partial file and never truncates an existing one; an output that
// is a device, FIFO or descriptor is written to as a stream instead, never replaced.
#pragma once

#include <atomic>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "image/output_target.h"
#include "luz/errors.h"  // FileError, WriteCancelled

namespace luz {

/// The text of an errno value ("No such file or directory").
std::string error_text(int err);

/// Whether a PendingFile is flushed to disk (fsync of the file before the rename and of its
/// folder after it): a checkpoint must survive a machine crash; an image, like any program's
/// output, is left to the page cache (the rename alone keeps it whole if luz dies), which spares
/// the disk's round trips (~1.5 ms of an 800×600 render on a virtio disk).
enum class Durability { page_cache, disk };

/// An output written under a temporary name `.<name>.tmp.<pid>.<random>` and renamed into place
/// by commit(), so that several files can be committed together; the temporary file is
/// removed if never committed. What is at the path decides how (resolve_output()):
/// - a regular file is replaced and keeps its mode and (where allowed) its owner; it gets a new
///   inode, so its other hard links keep the previous version;
/// - a symlink is written through: the file at the end of its chain is replaced, in its folder;
/// - a device, FIFO, socket or descriptor (/dev/null, /dev/stdout, /dev/fd/N) is a stream: the
///   bytes are kept and written to it by commit(), which never replaces or removes it;
/// - a folder is refused (FileError) before anything is written.
class PendingFile {
  public:
    /// Writes `bytes` to the temporary file (flushed to disk for Durability::disk); throws
    /// FileError.
    PendingFile(std::string path, const std::string& bytes,
                Durability durability = Durability::page_cache);
    PendingFile(std::string path, std::string&& bytes,
                Durability durability = Durability::page_cache);
    /// The same with the bytes given in pieces, written one after the other without first
    /// being joined (a checkpoint of 100 MB is written in a fraction of a second).
    PendingFile(std::string path, const std::vector<std::string_view>& pieces,
                Durability durability = Durability::page_cache);
    ~PendingFile();
    PendingFile(const PendingFile&) = delete;
    PendingFile& operator=(const PendingFile&) = delete;

    /// Whether commit() writes to a stream rather than renaming a file.
    bool is_stream() const { return target_.kind != OutputTarget::Kind::file; }

    /// Renames the temporary file onto its target, or writes the bytes to the stream (waiting
    /// for it in steps that check `cancel`); throws FileError (WriteCancelled when cancelled).
    void commit(const std::atomic<bool>* cancel = nullptr);

  private:
    void stage(const std::vector<std::string_view>& pieces);

    std::string path_;  ///< as given, for messages
    OutputTarget target_;
    std::string tmp_;
    std::string stream_bytes_;
    Durability durability_;
    bool committed_ = false;
};

/// Commits `files` together: the streams written first, then every file renamed into place, so
/// that a stream that fails (a full device, a reader gone, `cancel` set) leaves every file as it
/// was. Throws FileError.
void commit_together(const std::vector<PendingFile*>& files,
                     const std::atomic<bool>* cancel = nullptr);

/// Removes the temporary files of `path` (`.<name>.tmp.<pid>.<16 hex digits>`) left next to
/// it (next to the file its symlinks name) by processes of this machine that no longer run: a write
/// cut by SIGKILL (mpirun kills a run one second after its SIGTERM) or by a power cut. Those of
/// running processes stay. Returns how many were removed; never throws.
size_t remove_stale_temporaries(const std::string& path);

/// Writes `bytes` to `path` atomically (a PendingFile committed at once); throws FileError.
void write_file_atomically(const std::string& path, const std::string& bytes);

}  // namespace luz
