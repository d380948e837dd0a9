// `--stats FILE`: the render's statistics as JSON (docs/CLI.md).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "luz/stats_json.h"  // stats_json(), pipeline_name()
#include "render/stats.h"
#include "scene/scene_desc.h"

namespace luz {

/// The statistics of a render of `desc` as the JSON object `--stats` writes.
nlohmann::json stats_to_json(const RenderStats& stats, const SceneDesc& desc);

// stats_json() (luz/stats_json.h): stats_to_json() as the text of a `--stats` file.

}  // namespace luz
