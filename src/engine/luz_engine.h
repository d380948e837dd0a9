// The front ends' one internal header (the luz command, luz-mpi): what they need of the engine
// beyond the public API — a render kept in a checkpoint or sharing its tiles with other
// processes, the checks of every file a render touches, and the files the loader reads.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "luz/luz.h"
#include "luz/render_png.h"
#include "tile_share.h"

namespace luz {

class Checkpoint;

/// `--checkpoint FILE` (docs/CLI.md): the tiles a ray-traced render finished, kept in a file so
/// that an interrupted render continues where it stopped. Reads the file when it exists; throws
/// SceneError when it belongs to another render (`key`: the scene and options, as text).
class CheckpointFile {
  public:
    CheckpointFile(const std::string& path, const std::string& key);
    ~CheckpointFile();
    CheckpointFile(const CheckpointFile&) = delete;
    CheckpointFile& operator=(const CheckpointFile&) = delete;
    /// Writes the tiles finished so far (an interrupted render keeps them).
    void save();
    /// Deletes the file (the outputs are written: nothing left to continue).
    void remove();
    Checkpoint& checkpoint() { return *checkpoint_; }

  private:
    std::unique_ptr<Checkpoint> checkpoint_;
};

/// What a front end may hand a render besides the RenderOptions: a checkpoint, whose finished
/// tiles it skips and to which it adds its own, and a share of the tiles with other processes
/// (only those handed to this one are rendered here).
struct EngineHooks {
    CheckpointFile* checkpoint = nullptr;
    TileShare* share = nullptr;
};

/// render() and render_png() with `hooks`.
Frame render(const Scene& scene, const Settings& settings, const RenderOptions& options,
             const EngineHooks& hooks);
PngFrame render_png(const Scene& scene, const Settings& settings, const RenderOptions& options,
                    Encoding encoding, const EngineHooks& hooks);

/// Outputs written to temporary files as they are added (so that a signal during a later
/// encoding finds them there), renamed into place together by commit(); destroyed before
/// commit(), or on a failure, they leave no file.
class PendingOutputs {
  public:
    PendingOutputs();
    ~PendingOutputs();
    PendingOutputs(const PendingOutputs&) = delete;
    PendingOutputs& operator=(const PendingOutputs&) = delete;
    /// Writes `bytes` to a temporary file beside `path` (a stream: kept until commit()).
    void add(const std::string& path, std::string bytes);
    /// Writes the streams, then renames the others into place (commit_together()). Throws
    /// FileError (WriteCancelled when `cancel` is set while a stream waits for a reader).
    void commit(const std::atomic<bool>* cancel);

  private:
    struct Files;
    std::unique_ptr<Files> files_;
};

/// Checks before any work that `path` can be written: not a folder (a symlink to one
/// included), and a missing file's folder exists. A device, FIFO or descriptor passes (it is
/// written as a stream). Throws SceneError naming `origin`.
void check_writable_target(const std::string& path, const char* origin);

/// A file a render reads or writes and what names it in messages ("-o", "--aov depth",
/// "scene", "mesh or MTL file").
struct NamedFile {
    std::string path;
    std::string origin;
    bool output = true;
};

/// Throws SceneError when an output and any other of `files` are the same file: the same device
/// and inode, or, where nothing is yet, the same path once symlinks are resolved. The message
/// names both: "a.png: -o and --stats name the same file". Inputs may repeat.
void check_distinct_files(const std::vector<NamedFile>& files);

/// Reads the file at `path` whole; on failure returns nullopt and sets `reason`.
using TextReader =
    std::function<std::optional<std::string>(const std::string& path, std::string& reason)>;
/// Where the loader reads every file (empty: from disk; luz-mpi's other processes: the bytes
/// rank 0 sent). Process-wide: set it before loading, from one thread.
void set_file_source(TextReader source);

/// Called with every file the loader has read from disk, as it was read. Empty: none.
using FileObserver = std::function<void(const std::string& path, const std::string& text)>;
void set_file_observer(FileObserver observer);
const FileObserver& file_observer();

/// While alive, records every file the scene loader reads from disk (the scene, its OBJ and MTL
/// files), calling the observer set before it too (luz-mpi keeps them).
class InputFileRecorder {
  public:
    InputFileRecorder();
    ~InputFileRecorder();
    InputFileRecorder(const InputFileRecorder&) = delete;
    InputFileRecorder& operator=(const InputFileRecorder&) = delete;
    /// The paths read so far, as the loader named them.
    const std::vector<std::string>& files() const { return files_; }

  private:
    FileObserver previous_;
    std::mutex mutex_;
    std::vector<std::string> files_;
};

/// Whether `path`'s extension names the PNG format.
bool is_png_path(const std::string& path);

}  // namespace luz
