// What a front end's options become (docs/CLI.md, docs/PYTHON.md): the render options
// `--pipeline` … `--threshold` as scene overrides, `-o` checked before any work and the files it
// will make, and `--region` as a checked rectangle.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "luz/image.h"
#include "luz/scene_desc.h"
#include "luz/terms.h"

namespace luz {

/// The scene keys a front end's render options set (docs/CLI.md `--pipeline` … `--threshold`,
/// docs/PYTHON.md the Python keywords of the same names), each as the user gave it: a number's text
/// or a word; an unset one keeps the scene's value.
struct SceneOptions {
    std::optional<std::string> pipeline, model, width, height, max_depth, aa, samples, threshold;
};

/// The overrides that set those keys (render.pipeline, render.model, image.width,
/// image.height, render.max_depth, render.antialias.mode, .samples, .threshold), in that order,
/// each named after its command-line option ("--width 800") so that the loader checks and
/// reports them like the keys themselves: numbers go as typed, words as JSON strings.
std::vector<Override> option_overrides(const SceneOptions& options);

/// Checks before any work that `path` can take an image: a known extension (.png, .ppm, .pfm,
/// .exr) and an existing folder. `origin` names the option in messages (e.g. "-o").
/// Throws SceneError.
void check_output_path(const std::string& path, const char* origin);

/// The files a frame with the terms `aovs` makes when written to `path`, as
/// encode_frame_files() names them: the image, then `X.NAME.EXT` for each term (.exr: the one
/// file).
std::vector<std::string> frame_file_paths(const std::string& path,
                                          const std::vector<AovKind>& aovs);

/// Throws SceneError naming `what` (e.g. "--region 0,0,900,10", "region") when `region` is
/// empty or not inside the `image`'s pixels.
void check_region(const PixelRect& region, const ImageDesc& image, const std::string& what);

/// Parses "X0,Y0,X1,Y1" (four integers) as given to --region; throws SceneError naming
/// `--region TEXT` when it is not four integers, empty, or outside `image`.
PixelRect parse_region(const std::string& text, const ImageDesc& image);

}  // namespace luz
