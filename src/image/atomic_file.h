// Files written atomically: under a temporary name in the same folder, flushed, then renamed
// into place, so a failure never leaves a partial file and never truncates an existing one.
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

/// A file written under a temporary name `.<name>.tmp.<pid>.<random>` next to `path` and
/// renamed into place by commit(), so that several files can be committed together; the
/// temporary file is removed if never committed.
class PendingFile {
  public:
    /// Writes `bytes` to the temporary file and flushes it to disk; throws FileError.
    PendingFile(std::string path, const std::string& bytes);
    /// The same with the bytes given in pieces, written one after the other without first
    /// being joined (a checkpoint of 100 MB is written in a fraction of a second).
    PendingFile(std::string path, const std::vector<std::string_view>& pieces);
    ~PendingFile();
    PendingFile(const PendingFile&) = delete;
    PendingFile& operator=(const PendingFile&) = delete;

    /// Renames the temporary file to `path`; throws FileError.
    void commit();

  private:
    std::string path_, tmp_;
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
