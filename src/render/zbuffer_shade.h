// Where the zbuffer's fragments meet shade(): the frame its passes share and shade_fragment(),
// which turns one rasterized fragment into a colour (SPEC §1.1).
#pragma once

#include <cstring>
#include <type_traits>

#include "geometry/scene.h"
#include "math/lane8.h"
#include "render/aov.h"
#include "render/rasterizer.h"
#include "render/stats.h"
#include "render/zbuffer.h"
#include "scene/camera.h"
#include "shading/shade.h"
#include "shading/shade_lanes.h"

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

/// Whether shade_fragments_lanes() may shade fragment `frag` (not the background, not a light
/// sphere, a material shade_lanes() handles): its material index, else −1.
[[gnu::always_inline]] inline int32_t lane_material(const ZbufferFrame& f, const Fragment& frag) {
    if (frag.triangle == kNoTriangle) return -1;
    const int32_t material = f.geometry.triangle_material[frag.triangle];
    return material >= 0 && shades_in_lanes(f.settings.materials[material]) ? material : -1;
}

/// shade_fragment() of frags[at[k]] into out[at[k]] for k < n ≤ 8 (at[0 … 7] readable), eight
/// at a time: each
/// fragment's point built as fragment_point() builds it, then shade_lanes(). Every fragment
/// must have a lane_material() ≥ 0. The colours have shade_fragment()'s bits.
inline void shade_fragments_lanes(const ZbufferFrame& f, const Lighting& lighting,
                                  const Fragment* frags, const int* at, int n, Rgb* out,
                                  RenderStats& stats) {
    static_assert(sizeof(Vec3) == 3 * sizeof(float));
    const TriangleMesh& mesh = f.geometry.mesh;
    ShadingLanes p;
    // The fragments' triangles and barycentrics (lanes ≥ n repeat lane 0).
    static_assert(sizeof(Fragment) == 4 * sizeof(float));
    const Lane8i index = {0, 1, 2, 3, 4, 5, 6, 7};
    Lane8i fragment;  // at[k] … as offsets in floats
    std::memcpy(&fragment, at, sizeof fragment);
    fragment = (index < n ? fragment : at[0]) * 4;
    const float* fields = &frags->depth;
    const Lane8i triangle = (Lane8i)gather_lanes(fields + 1, fragment);
    const Lane8f b1 = gather_lanes(fields + 2, fragment), b2 = gather_lanes(fields + 3, fragment);
    // Their materials' constants: broadcast when all lanes share one (the usual case).
    const Lane8i material = gather_lanes(f.geometry.triangle_material.data(), triangle);
    const auto constants = [&](int k, const Material& m) {
        for (int a = 0; a < 3; ++a) {
            p.ka[a][k] = m.ka[a];
            p.kd[a][k] = m.kd[a];
            p.ks[a][k] = m.ks[a];
        }
        p.n[k] = m.n;
    };
    if (lane_bits(material == material[0]) == 0xFFu) {
        const Material& m = f.settings.materials[material[0]];
        for (int a = 0; a < 3; ++a) {
            p.ka[a] = lanes(m.ka[a]);
            p.kd[a] = lanes(m.kd[a]);
            p.ks[a] = lanes(m.ks[a]);
        }
        p.n = lanes(m.n);
    } else {
        for (int k = 0; k < kPacketLanes; ++k) constants(k, f.settings.materials[material[k]]);
    }
    // P and N interpolated from the triangle's vertices, as fragment_point() does; the
    // vertices are read once per distinct triangle of the eight (neighbours share them).
    Lane8f vp[3][3] = {}, vn[3][3] = {};  // [vertex][component]
    for (unsigned todo = 0xFFu; todo;) {
        const int32_t t = triangle[__builtin_ctz(todo)];
        const Lane8i same = triangle == t;
        todo &= ~lane_bits(same);
        const uint32_t* idx = &mesh.indices[3 * static_cast<size_t>(t)];
        for (int i = 0; i < 3; ++i) {
            const float* q = &mesh.positions[idx[i]].x;
            const float* m = &mesh.normals[idx[i]].x;
            for (int a = 0; a < 3; ++a) {
                vp[i][a] = lane_select(same, lanes(q[a]), vp[i][a]);
                vn[i][a] = lane_select(same, lanes(m[a]), vn[i][a]);
            }
        }
    }
    const Lane8f b0 = lanes(1.0f) - b1 - b2;
    Lane8f N[3];
    for (int a = 0; a < 3; ++a) {
        p.P[a] = vp[0][a] * b0 + vp[1][a] * b1 + vp[2][a] * b2;
        N[a] = vn[0][a] * b0 + vn[1][a] * b1 + vn[2][a] * b2;
    }
    const Lane8f inv_length = lanes(1.0f) / lane_sqrt(N[0] * N[0] + N[1] * N[1] + N[2] * N[2]);
    for (int a = 0; a < 3; ++a) p.N[a] = N[a] * inv_length;
    if (f.perspective) {  // S = normalize(eye − P)
        Lane8f to_eye[3];
        for (int a = 0; a < 3; ++a) to_eye[a] = f.camera.position[a] - p.P[a];
        const Lane8f inv = lanes(1.0f) / lane_sqrt(to_eye[0] * to_eye[0] + to_eye[1] * to_eye[1] +
                                                   to_eye[2] * to_eye[2]);
        for (int a = 0; a < 3; ++a) p.S[a] = to_eye[a] * inv;
    } else {
        for (int a = 0; a < 3; ++a) p.S[a] = lanes(f.camera.w[a]);
    }
    Lane8f I[3];
    shade_lanes(p, lighting, (1u << n) - 1, I);
    for (int k = 0; k < n; ++k) out[at[k]] = Rgb{I[0][k], I[1][k], I[2][k]};
    stats.samples += static_cast<uint64_t>(n);
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
