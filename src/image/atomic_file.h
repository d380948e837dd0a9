// Files written atomically: under a temporary name in the same folder, then renamed into place,
// so a failure never leaves a partial file and never truncates an existing one.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace luz {

/// A file that cannot be written; the message names it ("out.png: cannot write: …").
struct FileError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// Whether a PendingFile is flushed to disk (fsync of the file before the rename and of its
/// folder after it): a checkpoint must survive a machine crash; an image, like any program's
/// output, is left to the page cache (the rename alone keeps it whole if luz dies), which spares
/// the disk's round trips (~1.5 ms of an 800×600 render on a virtio disk).
enum class Durability { page_cache, disk };

/// A file written under a temporary name `.<name>.tmp.<pid>.<random>` next to `path` and
/// renamed into place by commit(), so that several files can be committed together; the
/// temporary file is removed if never committed.
class PendingFile {
  public:
    /// Writes `bytes` to the temporary file (flushed to disk for Durability::disk); throws
    /// FileError.
    PendingFile(std::string path, const std::string& bytes,
                Durability durability = Durability::page_cache);
    /// The same with the bytes given in pieces, written one after the other without first
    /// being joined (a checkpoint of 100 MB is written in a fraction of a second).
    PendingFile(std::string path, const std::vector<std::string_view>& pieces,
                Durability durability = Durability::page_cache);
    ~PendingFile();
    PendingFile(const PendingFile&) = delete;
    PendingFile& operator=(const PendingFile&) = delete;

    /// Renames the temporary file to `path`; throws FileError.
    void commit();

  private:
    std::string path_, tmp_;
    Durability durability_;
    bool committed_ = false;
};

/// Removes the temporary files of `path` (`.<name>.tmp.<pid>.<16 hex digits>`) left next to
/// it by processes of this machine that no longer run: a write cut by SIGKILL (mpirun kills a
/// run one second after its SIGTERM) or by a power cut. Those of running processes stay.
/// Returns how many were removed; never throws.
size_t remove_stale_temporaries(const std::string& path);

/// Writes `bytes` to `path` atomically (a PendingFile committed at once); throws FileError.
void write_file_atomically(const std::string& path, const std::string& bytes);

}  // namespace luz
