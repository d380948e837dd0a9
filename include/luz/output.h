// luz's public API, part 3: outputs. A frame to an image file (PNG, PPM, PFM, EXR by extension,
// written atomically), its statistics and ray trees as JSON, and the output path's check.
#pragma once

#include <atomic>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "luz/render.h"

namespace luz {

/// Checks before any work that `path` can take an image: a known extension (.png, .ppm, .pfm,
/// .exr) and an existing folder. `origin` names the option in messages (e.g. "-o").
/// Throws SceneError.
void check_output_path(const std::string& path, const char* origin);

/// The files a frame with the terms `aovs` makes when written to `path`, as
/// encode_frame_files() names them: the image, then `X.NAME.EXT` for each term (.exr: the one
/// file).
std::vector<std::string> frame_file_paths(const std::string& path,
                                          const std::vector<AovKind>& aovs);

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

/// The --aa-mask picture of a frame rendered with RenderOptions::want_aa_mask.
Image frame_aa_mask(const Frame& frame);

/// The bytes of `image` as the file `path` names (format by extension; 8-bit formats with
/// `encoding`, float formats raw).
std::string encode_image(const std::string& path, const Image& image, Encoding encoding);

/// The image as 8-bit RGBA bytes (alpha 255), row 0 first, its values encoded as the 8-bit
/// files encode them (e.g. for a texture).
std::vector<uint8_t> rgba8(const Image& image, Encoding encoding);

/// Writes `image` to `path` atomically (format by extension; 8-bit formats with `encoding`).
/// Throws FileError.
void write_image(const std::string& path, const Image& image, Encoding encoding);

/// Writes the bytes of each (path, bytes) to a temporary file, then renames them all into place
/// (a failure leaves none of them); a stream among them is waited for in steps that check
/// `cancel`. Throws FileError (WriteCancelled when cancelled).
void write_files_together(std::vector<std::pair<std::string, std::string>> files,
                          const std::atomic<bool>* cancel = nullptr);

/// The name of a pipeline as the scene file spells it ("zbuffer", "raycast", "raytrace").
const char* pipeline_name(Pipeline p);

/// The statistics of a render of `desc` as the JSON text `--stats` writes (docs/CLI.md).
std::string stats_json(const RenderStats& stats, const SceneDesc& desc);

/// Bytes of the process's peak resident memory (getrusage ru_maxrss).
uint64_t peak_resident_bytes();

/// The ray tree of pixel (x, y) as JSON text (`luz view --click`, luz.ray_tree): the pixel, the
/// colour the render gave it, and every node with its terms, objects and materials named as in
/// the scene.
std::string ray_tree_json(const RayTree& tree, const SceneDesc& desc, int x, int y,
                          const Rgb& pixel);

/// Short names for the inspector: "objects.2 (sphere)", "material red", "lights.0".
std::string object_label(const SceneDesc& desc, int object);
std::string material_label(const SceneDesc& desc, int material);

}  // namespace luz
