// --checkpoint FILE (SPEC §3): the finished work items (tiles) of a long render kept in a file,
// written atomically now and then and when interrupted, so that a rerun with the same scene and
// options continues where it stopped and ends with the bits of an uninterrupted render.
#pragma once

#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

namespace luz {

class Checkpoint {
  public:
    /// A checkpoint in `path` for a render whose scene and options hash to `key`. Loads the
    /// finished items when the file exists; throws InputError naming the file when it is not a
    /// luz checkpoint, is damaged or truncated, of another version, or made for another scene
    /// or options (the file is then left as it was).
    Checkpoint(std::string path, uint64_t key);

    /// Called by the render with its number of work items (the sampler's tiles; adaptive: both
    /// passes); throws InputError when the file holds another number.
    void start(size_t items);

    /// Whether item `i` was finished by an earlier run, and its bytes.
    bool done(size_t i) const { return i < items_.size() && items_[i].done; }
    std::string_view data(size_t i) const { return items_[i].bytes; }

    /// Records item `i` as finished (any thread); writes the file when the last write is at
    /// least `interval` old.
    void finish(size_t i, std::string bytes);

    /// Writes the file now (atomically: a temporary file renamed into place).
    void save();

    /// Removes the file (after the output is written).
    void remove();

    /// How many items are finished (loaded or recorded).
    size_t finished() const;

    const std::string& path() const { return path_; }

    /// Seconds between writes while rendering.
    static constexpr double kInterval = 10.0;

  private:
    struct Item {
        bool done = false;
        std::string bytes;
    };
    void save_locked();

    std::string path_;
    uint64_t key_;
    std::vector<Item> items_;
    mutable std::mutex mutex_;
    std::chrono::steady_clock::time_point last_save_;
};

/// FNV-1a, 64 bits: the key of a render's scene and options.
uint64_t fingerprint(std::string_view text);

}  // namespace luz
