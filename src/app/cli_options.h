// The `luz render` options (docs/CLI.md) and how the scene-overriding ones become Overrides.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "luz/scene.h"

namespace CLI {
class App;
}

namespace luz {

/// Everything `luz render` was given. BuiltScene-overriding values are kept as the user typed them
/// and validated by the scene loader, so that every bad value is reported the same way.
struct RenderArgs {
    std::string scene;   ///< a file path or demo:NAME
    std::string output;  ///< empty: the scene's name + ".png"
    std::optional<std::string> pipeline, model, width, height, max_depth, aa, samples, threshold;
    std::vector<std::string> sets;  ///< each "PATH=JSON", in the order given
    int threads = 0;                ///< 0: all cores
    std::string stats_file;         ///< empty: no statistics file
    std::string aa_mask_file;       ///< empty: no image of the adaptively refined pixels
    std::string aovs;               ///< --aov NAME[,NAME…] or all (docs/SCENES.md#terms)
    std::string checkpoint;         ///< --checkpoint FILE: finished tiles kept there (docs/CLI.md)
    std::optional<std::string> region;  ///< --region X0,Y0,X1,Y1 as typed; unset: whole image
    std::optional<std::string> frames;  ///< --frames A:B or all as typed; unset: frame 0 only
    bool quiet = false;
    std::optional<uint64_t> max_memory;  ///< bytes; default half of physical memory
};

/// Declares the render options on `cmd`, storing into `o`.
void add_render_options(CLI::App& cmd, RenderArgs& o);

/// The overrides for the loader: the --set ones in order, then one per scene-overriding
/// option (origin = the option's name). Throws InputError for a malformed --set.
std::vector<Override> overrides_of(const RenderArgs& o);

}  // namespace luz
