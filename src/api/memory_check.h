// The memory check made before rendering: refuse an image too large for this machine
// (exit 2) instead of failing, or being killed, halfway through.
#pragma once

#include <cstdint>
#include <optional>

#include "luz/memory.h"
#include "scene/scene_desc.h"

namespace luz {

/// Bytes a render of W×H pixels needs: float image, depth, g-buffer and the 8-bit copy.
uint64_t estimate_render_bytes(int width, int height);

/// What a render of a scene needs, by part (estimates made before anything is built).
struct MemoryEstimate {
    uint64_t image = 0;         ///< estimate_render_bytes(W, H) and the per-term images
    uint64_t antialias = 0;     ///< adaptive: the (W+1)×(H+1) corner colours and the mask
    uint64_t tessellation = 0;  ///< the zbuffer's triangles of curved shapes
    uint64_t meshes = 0;        ///< mesh triangles: shared vertices, indices, BVH share
    uint64_t objects = 0;       ///< every object's description, built shape and BVH share
    uint64_t total() const { return image + antialias + tessellation + meshes + objects; }
};

/// The estimate for `desc` (its meshes already loaded): image; antialiasing (grid works in
/// bounded tiles, adaptive keeps every pixel corner); the triangles of each curved shape at
/// tessellation t in the zbuffer (tessellated_triangle_count(): ~t² a sphere, 2t a cylinder's
/// side); per mesh triangle its share of vertices, indices and BVH;
/// per object its description and built shape; `aov_count` per-term images (docs/SCENES.md#terms)
/// asked for besides the image.
MemoryEstimate estimate_memory(const SceneDesc& desc, int aov_count = 0);

// default_memory_limit() and check_memory() are declared with the API (luz/memory.h).

}  // namespace luz
