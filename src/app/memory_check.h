// The memory check made before rendering: refuse an image too large for this machine
// (exit 2) instead of failing, or being killed, halfway through.
#pragma once

#include <cstdint>
#include <optional>

#include "scene/scene_desc.h"

namespace luz {

/// Bytes a render of W×H pixels needs: float image, depth, g-buffer and the 8-bit copy.
uint64_t estimate_render_bytes(int width, int height);

/// Half of the physical memory (or of the cgroup limit, when smaller).
uint64_t default_memory_limit();

/// Throws InputError naming the scene and `image.width` when the image needs more than
/// `limit` bytes (default_memory_limit() when not given).
void check_memory(const SceneDesc& desc, std::optional<uint64_t> limit = std::nullopt);

}  // namespace luz
