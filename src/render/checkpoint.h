// --checkpoint FILE (docs/CLI.md): the finished work items (tiles) of a long render kept in a file,
// written atomically now and then and when interrupted, so that a rerun with the same scene and
// options continues where it stopped and ends with the bits of an uninterrupted render.
#pragma once

#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "render/checkpoint_file.h"

namespace luz {

class Checkpoint {
  public:
    /// A checkpoint in `path` for a render whose scene and options hash to `key`. Reads and
    /// checks the file when it exists (render/checkpoint_file.h); throws InputError naming the
    /// file when it is not a regular file, not a luz checkpoint, damaged or truncated, of another
    /// version, or made for another scene or options (the file is then left as it was).
    Checkpoint(std::string path, uint64_t key);

    /// Called by the render with its number of work items (the sampler's tiles; adaptive: both
    /// passes); throws InputError when the file holds another number. Only then is memory
    /// given to the items.
    void start(size_t items);

    /// Whether item `i` was finished by an earlier run, and its bytes.
    bool done(size_t i) const { return i < items_.size() && items_[i].done; }
    std::string_view data(size_t i) const { return items_[i].bytes; }

    /// Records item `i` as finished (any thread); writes the file when the last write is at
    /// least interval() old. A write that fails does not stop the render: the first failure's
    /// message is returned (to be shown as a warning), later ones "", and the next write is
    /// tried an interval later.
    [[nodiscard]] std::string finish(size_t i, std::string bytes);

    /// Writes the file now (atomically: a temporary file renamed into place); throws FileError.
    void save();

    /// Removes the file (after the output is written).
    void remove();

    /// How many items are finished (loaded or recorded).
    size_t finished() const;

    const std::string& path() const { return path_; }

    /// Seconds between writes while rendering: 10, or LUZ_CHECKPOINT_SECONDS when it is a number
    /// of seconds > 0 (e.g. 0.5 for tests, 60 for a slow disk).
    static double interval();

  private:
    struct Item {
        bool done = false;
        uint32_t crc = 0;  ///< tile_checksum() of the bytes
        std::string bytes;
    };
    void save_locked();

    std::string path_;
    uint64_t key_;
    std::string file_;             ///< the file's bytes, until start() takes its tiles
    CheckpointContents contents_;  ///< what they hold
    bool loaded_ = false;
    bool started_ = false;  ///< start() was called: items_ holds the items
    std::vector<Item> items_;
    mutable std::mutex mutex_;
    std::chrono::steady_clock::time_point last_save_;
    double interval_;
    bool warned_ = false;  ///< a failed write has been reported
};

/// FNV-1a, 64 bits: the key of a render's scene and options.
uint64_t fingerprint(std::string_view text);

}  // namespace luz
