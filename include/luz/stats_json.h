// `--stats FILE` (docs/CLI.md): a render's statistics as the JSON text the luz command and
// Python's Frame.stats_json() write.
#pragma once

#include <string>

#include "luz/scene_desc.h"
#include "luz/stats.h"

namespace luz {

/// The statistics of a render of `desc` as the JSON text `--stats` writes (docs/CLI.md).
std::string stats_json(const RenderStats& stats, const SceneDesc& desc);

/// The name of a pipeline as the scene file spells it ("zbuffer", "raycast", "raytrace").
const char* pipeline_name(Pipeline p);

}  // namespace luz
