// The render options every front end offers (`luz render --width …`, `luz.render(width=…)`)
// turned into scene overrides: one mapping, so that both mean exactly the same.
#include <nlohmann/json.hpp>

#include "luz/options.h"

namespace luz {

std::vector<Override> option_overrides(const SceneOptions& o) {
    std::vector<Override> out;
    // Numbers go to the loader as typed (it checks their type and range); words are quoted.
    auto number = [&](const std::optional<std::string>& v, const char* path, const char* opt) {
        if (v) out.push_back(Override{path, *v, opt});
    };
    auto word = [&](const std::optional<std::string>& v, const char* path, const char* opt) {
        if (v) out.push_back(Override{path, nlohmann::json(*v).dump(), opt});
    };
    word(o.pipeline, "render.pipeline", "--pipeline");
    word(o.model, "render.model", "--model");
    number(o.width, "image.width", "--width");
    number(o.height, "image.height", "--height");
    number(o.max_depth, "render.max_depth", "--max-depth");
    word(o.aa, "render.antialias.mode", "--aa");
    number(o.samples, "render.antialias.samples", "--samples");
    number(o.threshold, "render.antialias.threshold", "--threshold");
    return out;
}

}  // namespace luz
