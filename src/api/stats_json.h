// `--stats FILE`: the render's statistics as JSON (docs/CLI.md).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "luz/output.h"
#include "render/stats.h"
#include "scene/scene_desc.h"

namespace luz {

/// The name of a pipeline as the scene file spells it.
const char* pipeline_name(Pipeline p);

/// Bytes of the process's peak resident memory (getrusage ru_maxrss).
uint64_t peak_resident_bytes();

/// The statistics of a render of `desc` as the JSON object `--stats` writes.
nlohmann::json stats_to_json(const RenderStats& stats, const SceneDesc& desc);

// stats_json() (luz/output.h): stats_to_json() as the text of a `--stats` file.

}  // namespace luz
