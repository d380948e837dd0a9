// The zbuffer pipeline: tessellate, project, clip, rasterize with a float depth buffer, and
// shade every covered pixel with shade() (docs/SCENES.md#models: the model evaluated at every
// point).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "geometry/scene.h"
#include "geometry/triangle_mesh.h"
#include "image/image.h"
#include "render/render.h"
#include "render/stats.h"

namespace luz {

class RasterSpare;

/// The scene's triangles, tessellated once, in world space; a triangle's material is that of
/// its shape. Planes and light spheres are included (planes as view-covering quads).
struct ZbufferGeometry {
    TriangleMesh mesh;
    std::vector<int32_t> triangle_material;  ///< material index, or −1 − light for a light sphere
    std::vector<Vec3> triangle_normal;       ///< unit outward geometric normal per triangle
    /// The last frame's binning buffers, for the next frame to reuse (set by prepare_zbuffer).
    std::shared_ptr<RasterSpare> raster_spare;
};

/// Tessellates every shape of `scene` at its `render.tessellation` level.
ZbufferGeometry prepare_zbuffer(const BuiltScene& scene, const Settings& settings);

/// Rasterizes prepared geometry into `out` (scene.desc.image size, background filled).
void render_zbuffer(const BuiltScene& scene, const Settings& settings,
                    const ZbufferGeometry& geometry, const RenderControl& control, Image& out,
                    RenderStats& stats);

}  // namespace luz
