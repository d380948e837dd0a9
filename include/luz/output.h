// luz's public API, part 3: outputs. A frame to an image file (PNG, PPM, PFM, EXR by extension,
// written atomically), with its per-term images.
#pragma once

#include <atomic>
#include <string>
#include <utility>
#include <vector>

#include "luz/render.h"

namespace luz {

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
/// show depth, normal and tests as pictures (luz/pictures.h). Each entry: (path, bytes).
std::vector<std::pair<std::string, std::string>> encode_frame_files(const Frame& frame,
                                                                    const std::string& path,
                                                                    Encoding encoding);

/// Writes encode_frame_files() atomically: every file to a temporary one first, then all
/// renamed into place (commit_together()), so that a failure leaves none of them. A stream
/// among them (a FIFO without a reader) is waited for in steps that check `cancel`. Throws
/// FileError (WriteCancelled when cancelled).
void write_frame_files(const Frame& frame, const std::string& path, Encoding encoding,
                       const std::atomic<bool>* cancel = nullptr);

/// The bytes of `image` as the file `path` names (format by extension; 8-bit formats with
/// `encoding`, float formats raw).
std::string encode_image(const std::string& path, const Image& image, Encoding encoding);

/// Writes `image` to `path` atomically (format by extension; 8-bit formats with `encoding`).
/// Throws FileError.
void write_image(const std::string& path, const Image& image, Encoding encoding);

/// Writes the bytes of each (path, bytes) to a temporary file, then renames them all into place
/// (a failure leaves none of them); a stream among them is waited for in steps that check
/// `cancel`. Throws FileError (WriteCancelled when cancelled).
void write_files_together(std::vector<std::pair<std::string, std::string>> files,
                          const std::atomic<bool>* cancel = nullptr);

}  // namespace luz
