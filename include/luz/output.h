// luz's public API, part 3: outputs. A frame to an image file (PNG, PPM, PFM, EXR by extension,
// written atomically), its statistics as JSON, and the checks made before a long render.
#pragma once

#include <atomic>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "api/memory_check.h"
#include "api/ray_tree_json.h"
#include "api/stats_json.h"
#include "image/atomic_file.h"
#include "image/image_io.h"
#include "luz/render.h"

namespace luz {

/// Checks before any work that `path` can take an image: a known extension (.png, .ppm, .pfm,
/// .exr) and an existing folder. `origin` names the option in messages (e.g. "-o").
/// Throws SceneError.
void check_output_path(const std::string& path, const char* origin);

/// Checks before any work that `path` can be written: not a folder (a symlink to one
/// included), and a missing file's folder exists. A device, FIFO or descriptor passes (it is
/// written as a stream, see PendingFile). Throws SceneError naming `origin`.
void check_writable_target(const std::string& path, const char* origin);

/// The files a frame with the terms `aovs` makes when written to `path`, as
/// encode_frame_files() names them: the image, then `X.NAME.EXT` for each term (.exr: the one
/// file).
std::vector<std::string> frame_file_paths(const std::string& path,
                                          const std::vector<AovKind>& aovs);

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

/// While alive, records every file the scene loader reads from disk (the scene, its OBJ and MTL
/// files), calling the observer set before it too (set_file_observer(); MPI keeps them).
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

/// The bytes of the image file `path` names (format by extension; 8-bit formats encoded with
/// `encoding`, float formats raw).
std::string encode_frame(const Frame& frame, const std::string& path, Encoding encoding);

/// Writes the frame's image to `path` atomically (a temporary file renamed into place: a
/// failure leaves no file and never truncates an existing one; a symlink is written through,
/// a device, FIFO or descriptor written as a stream: PendingFile). Throws FileError.
void write_frame(const Frame& frame, const std::string& path, Encoding encoding);

/// The files a frame makes when written to `path`: the image, then each per-term image — with
/// `-o X.EXT`, `X.NAME.EXT` in the same format; for .exr, one file X.exr holding the image and
/// every term as layers (`NAME.R`, `NAME.G`, `NAME.B`; `depth.Y`, `tests.Y`). 8-bit formats
/// show depth, normal and tests as pictures (aov_picture()). Each entry: (path, bytes).
std::vector<std::pair<std::string, std::string>> encode_frame_files(const Frame& frame,
                                                                    const std::string& path,
                                                                    Encoding encoding);

/// Writes encode_frame_files() atomically: every file to a temporary one first, then all
/// renamed into place (commit_together()), so that a failure leaves none of them. A stream
/// among them (a FIFO without a reader) is waited for in steps that check `cancel`. Throws
/// FileError (WriteCancelled when cancelled).
void write_frame_files(const Frame& frame, const std::string& path, Encoding encoding,
                       const std::atomic<bool>* cancel = nullptr);

/// The 8-bit picture of a per-term image: colour terms as they are; depth near bright (the
/// nearest hit white, the farthest dark, misses black); normal as 0.5 + 0.5·N; tests through
/// a perceptual colour map (viridis) from 0 to the frame's largest count.
Image aov_picture(const Aov& aov);

/// viridis at f in [0, 1] (the colour map of the `tests` picture; README shows its scale).
Rgb viridis(float f);

/// The --stats JSON text of a frame rendered from `desc` (the description whose settings
/// were rendered: its pipeline, model, antialiasing, source and accel are reported).
std::string frame_stats_json(const Frame& frame, const SceneDesc& desc);

/// The --aa-mask picture of a frame rendered with RenderOptions::want_aa_mask.
Image frame_aa_mask(const Frame& frame);

}  // namespace luz
