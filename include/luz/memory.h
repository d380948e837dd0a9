// Memory: the cap on what loading a scene may use, the check made before rendering (refuse an
// image too large for this machine rather than fail halfway), and the process's peak.
#pragma once

#include <cstdint>
#include <optional>

#include "luz/scene_desc.h"

namespace luz {

/// The cap on what loading a scene may use (its text, OBJ files, meshes), in bytes.
void set_memory_limit(uint64_t bytes);

/// Half of the physical memory (or of the cgroup limit, when smaller): check_memory()'s default
/// cap, and the one a front end gives set_memory_limit().
uint64_t default_memory_limit();

/// Throws SceneError naming the scene and the key of the largest part (`image.width`,
/// `render.tessellation`, `objects.N.file`, `objects`) when rendering `desc` with `aov_count`
/// per-term images needs more than `limit` bytes (default: default_memory_limit()).
void check_memory(const SceneDesc& desc, std::optional<uint64_t> limit = std::nullopt,
                  int aov_count = 0);

/// Bytes of the process's peak resident memory (getrusage ru_maxrss).
uint64_t peak_resident_bytes();

}  // namespace luz
