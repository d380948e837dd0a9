// Where the zbuffer's fragments meet shade(): the frame its passes share and shade_fragment(),
// which turns one rasterized fragment into a colour (SPEC §1.1).
#pragma once

#include <type_traits>

#include "geometry/scene.h"
#include "render/aov.h"
#include "render/rasterizer.h"
#include "render/stats.h"
#include "render/zbuffer.h"
#include "scene/camera.h"
#include "shading/shade.h"

namespace luz {

/// One zbuffer frame: the scene, its prepared geometry, the camera and the binned rasterizer.
struct ZbufferFrame {
    const BuiltScene& scene;
    const Settings& settings;  ///< camera, lights, materials … of this render
    const ZbufferGeometry& geometry;
    const Rasterizer& raster;
    Camera camera;
    bool perspective;
};

/// The lighting shade() is given: the scene's model, ambient light, K and lights.
inline Lighting lighting_of(const Settings& desc) {
    return {desc.render.model, desc.ambient, desc.attenuation_k, desc.lights};
}

/// The surface point of a fragment of an object's triangle (not a light sphere's).
[[gnu::always_inline]] inline ShadingPoint fragment_point(const ZbufferFrame& f,
                                                          const Fragment& frag, int32_t material) {
    const TriangleMesh& mesh = f.geometry.mesh;
    const uint32_t* idx = &mesh.indices[3 * static_cast<size_t>(frag.triangle)];
    const float b0 = 1.0f - frag.b1 - frag.b2;
    ShadingPoint p;
    p.P = mesh.positions[idx[0]] * b0 + mesh.positions[idx[1]] * frag.b1 +
          mesh.positions[idx[2]] * frag.b2;
    p.N = normalize(mesh.normals[idx[0]] * b0 + mesh.normals[idx[1]] * frag.b1 +
                    mesh.normals[idx[2]] * frag.b2);
    p.Ng = f.geometry.triangle_normal[frag.triangle];
    p.S = f.perspective ? normalize(f.camera.position - p.P) : f.camera.w;
    p.material = &f.settings.materials[material];
    return p;
}

/// The colour of one fragment: the background, a light sphere's clamped colour, or shade() at
/// its point (counted as a sample).
[[gnu::always_inline]] inline Rgb shade_fragment(const ZbufferFrame& f, const Lighting& lighting,
                                                 const Fragment& frag, RenderStats& stats) {
    const Settings& desc = f.settings;
    if (frag.triangle == kNoTriangle) return desc.image.background;
    const int32_t material = f.geometry.triangle_material[frag.triangle];
    if (material < 0) {  // a visible light sphere: the light's clamped colour
        return clamp01(desc.lights[-1 - material].intensity);
    }
    ++stats.samples;
    return shade(fragment_point(f, frag, material), lighting, AllVisible{});
}

/// The same fragment's colour with its terms (SPEC §1.5; `tests`: the point's depth tests).
/// Its colour has the bits shade_fragment() gives.
TermSample shade_fragment_terms(const ZbufferFrame& f, const Lighting& lighting,
                                const Fragment& frag, uint32_t tests, RenderStats& stats);

/// A fragment's sample as the sampler asks for it: its colour (Rgb) or colour and terms.
template <class S>
S fragment_sample(const ZbufferFrame& f, const Lighting& lighting, const Fragment& frag,
                  uint32_t tests, RenderStats& stats) {
    if constexpr (std::is_same_v<S, Rgb>) {
        return shade_fragment(f, lighting, frag, stats);
    } else {
        return shade_fragment_terms(f, lighting, frag, tests, stats);
    }
}

}  // namespace luz
