// Where the zbuffer's fragments meet shade(): the frame its passes share and shade_fragment(),
// which turns one rasterized fragment into a colour (docs/SCENES.md#ray-tracing).
#pragma once

#include <cstddef>
#include <cstring>
#include <type_traits>
#include <vector>

#include "geometry/scene.h"
#include "math/lane8.h"
#include "math/lane_count.h"
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

/// The lighting shade() is given: the scene's model, ambient light, K, lights and law.
inline Lighting lighting_of(const Settings& desc) {
    return {desc.render.model, desc.ambient, desc.attenuation_k, desc.lights, desc.attenuation};
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

namespace zbuffer_detail {

/// The fields of eight consecutive fragments f[0 … 7], lane k holding f[k]'s.
inline void load_fragments(const Fragment* f, Lane8f& depth, Lane8i& triangle, Lane8f& b1,
                           Lane8f& b2) {
    static_assert(sizeof(Fragment) == 4 * sizeof(float) && offsetof(Fragment, triangle) == 4 &&
                  offsetof(Fragment, b1) == 8 && offsetof(Fragment, b2) == 12);
    // fragments (0 1), (2 3), (4 5), (6 7), loaded straight into registers (a copy through
    // the stack stalls the loads on its 16-byte stores)
    const char* bytes = reinterpret_cast<const char*>(f);
    Lane8f v[4];
    for (int i = 0; i < 4; ++i) v[i] = load_lanes(bytes + i * sizeof(Lane8f));
    // (depth triangle) and (b1 b2) of fragments 0 … 3, then 4 … 7
    const Lane8f dt_lo = __builtin_shufflevector(v[0], v[1], 0, 4, 8, 12, 1, 5, 9, 13);
    const Lane8f dt_hi = __builtin_shufflevector(v[2], v[3], 0, 4, 8, 12, 1, 5, 9, 13);
    const Lane8f bb_lo = __builtin_shufflevector(v[0], v[1], 2, 6, 10, 14, 3, 7, 11, 15);
    const Lane8f bb_hi = __builtin_shufflevector(v[2], v[3], 2, 6, 10, 14, 3, 7, 11, 15);
    depth = __builtin_shufflevector(dt_lo, dt_hi, 0, 1, 2, 3, 8, 9, 10, 11);
    triangle = (Lane8i)__builtin_shufflevector(dt_lo, dt_hi, 4, 5, 6, 7, 12, 13, 14, 15);
    b1 = __builtin_shufflevector(bb_lo, bb_hi, 0, 1, 2, 3, 8, 9, 10, 11);
    b2 = __builtin_shufflevector(bb_lo, bb_hi, 4, 5, 6, 7, 12, 13, 14, 15);
}

/// out[k] = (r[k], g[k], b[k]) for the eight lanes k: three 32-byte stores.
inline void store_colours(Rgb* out, Lane8f r, Lane8f g, Lane8f b) {
    static_assert(sizeof(Rgb) == 3 * sizeof(float));
    const Lane8f rg_lo = __builtin_shufflevector(r, g, 0, 8, 1, 9, 2, 10, 3, 11);
    const Lane8f rg_hi = __builtin_shufflevector(r, g, 4, 12, 5, 13, 6, 14, 7, 15);
    const Lane8f rg_mid = __builtin_shufflevector(rg_lo, rg_hi, 6, 7, 8, 9, 10, 11, 12, 13);
    const Lane8f v[3] = {__builtin_shufflevector(rg_lo, b, 0, 1, 8, 2, 3, 9, 4, 5),
                         __builtin_shufflevector(rg_mid, b, 10, 0, 1, 11, 2, 3, 12, 4),
                         __builtin_shufflevector(rg_hi, b, 3, 13, 4, 5, 14, 6, 7, 15)};
    char* bytes = reinterpret_cast<char*>(out);
    for (int i = 0; i < 3; ++i) store_lanes(bytes + i * sizeof(Lane8f), v[i]);
}

}  // namespace zbuffer_detail

/// shade_fragment() of eight consecutive fragments frags[0 … 7] into out[0 … 7], the objects'
/// fragments side by side: each point built as fragment_point() builds it (a checker's Ka and
/// Kd chosen per lane), then shade_lanes(). The rest (background, light spheres) as
/// shade_fragment() gives them. Every colour has shade_fragment()'s bits.
inline void shade_fragments_lanes(const ZbufferFrame& f, const Lighting& lighting,
                                  const Fragment* frags, Rgb* out, RenderStats& stats) {
    using namespace zbuffer_detail;
    const Rgb& background = f.settings.image.background;
    Lane8f depth, b1, b2;
    Lane8i triangle;
    load_fragments(frags, depth, triangle, b1, b2);
    const unsigned covered =
        lane_bits(lane_ne(triangle, lanes_i(static_cast<int32_t>(kNoTriangle))));
    if (!covered) {
        for (int k = 0; k < kPacketLanes; ++k) out[k] = background;
        return;
    }
    // The lanes shaded side by side: their materials' constants, broadcast when they share one.
    const int32_t first = triangle[__builtin_ctz(covered)];
    triangle = lane_select(lane_mask(covered), triangle, lanes_i(first));  // uncovered: first's
    const TriangleMesh& mesh = f.geometry.mesh;
    const Lane8i material = gather_lanes(f.geometry.triangle_material.data(), triangle);
    const std::vector<Material>& materials = f.settings.materials;
    ShadingLanes p;
    unsigned active = 0;
    unsigned checkered = 0;  // lanes whose Ka, Kd a checker chooses, once P is known
    const auto is_schlick = [](const Material& m) {
        return m.reflectance == Reflectance::schlick ? -1 : 0;
    };
    if (lane_bits(lane_eq(material, lanes_i(material[0]))) == 0xFFu) {
        const int32_t m = material[0];
        if (m >= 0) {
            active = covered;
            if (materials[m].checker) checkered = covered;
            for (int a = 0; a < 3; ++a) {
                p.ka[a] = lanes(materials[m].ka[a]);
                p.kd[a] = lanes(materials[m].kd[a]);
                p.ks[a] = lanes(materials[m].ks[a]);
            }
            p.n = lanes(materials[m].n);
            p.schlick = lanes_i(is_schlick(materials[m]));
        }
    } else {
        for (int a = 0; a < 3; ++a) p.ka[a] = p.kd[a] = p.ks[a] = lanes(0.0f);
        p.n = lanes(1.0f);
        for (unsigned c = covered; c; c &= c - 1) {
            const int k = __builtin_ctz(c);
            const int32_t m = material[k];
            if (m < 0) continue;  // a light sphere
            active |= 1u << k;
            if (materials[m].checker) checkered |= 1u << k;
            for (int a = 0; a < 3; ++a) {
                p.ka[a][k] = materials[m].ka[a];
                p.kd[a][k] = materials[m].kd[a];
                p.ks[a][k] = materials[m].ks[a];
            }
            p.n[k] = materials[m].n;
            p.schlick[k] = is_schlick(materials[m]);
        }
    }
    Lane8f I[3] = {lanes(background.x), lanes(background.y), lanes(background.z)};
    if (active) {
        // P and N interpolated from the triangle's vertices, as fragment_point() does; the
        // vertices are read once per distinct triangle of the eight (neighbours share them).
        Lane8f vp[3][3] = {}, vn[3][3] = {};  // [vertex][component]
        for (unsigned pending = active; pending;) {
            const int32_t t = triangle[__builtin_ctz(pending)];
            const Lane8i same = lane_eq(triangle, lanes_i(t));
            pending &= ~lane_bits(same);
            const uint32_t* idx = &mesh.indices[3 * static_cast<size_t>(t)];
            for (int i = 0; i < 3; ++i) {
                const float* q = &mesh.positions[idx[i]].x;
                const float* n = &mesh.normals[idx[i]].x;
                for (int a = 0; a < 3; ++a) {
                    vp[i][a] = lane_select(same, lanes(q[a]), vp[i][a]);
                    vn[i][a] = lane_select(same, lanes(n[a]), vn[i][a]);
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
        // A checker's cell at P (against the triangle's geometric normal), as shade() picks it.
        for (unsigned c = checkered; c; c &= c - 1) {
            const int k = __builtin_ctz(c);
            const SurfaceConstants sc =
                surface_constants(materials[material[k]], {p.P[0][k], p.P[1][k], p.P[2][k]},
                                  f.geometry.triangle_normal[triangle[k]]);
            for (int a = 0; a < 3; ++a) {
                p.ka[a][k] = sc.ka[a];
                p.kd[a][k] = sc.kd[a];
            }
        }
        if (f.perspective) {  // S = normalize(eye − P)
            Lane8f to_eye[3];
            for (int a = 0; a < 3; ++a) to_eye[a] = f.camera.position[a] - p.P[a];
            const Lane8f inv =
                lanes(1.0f) /
                lane_sqrt(to_eye[0] * to_eye[0] + to_eye[1] * to_eye[1] + to_eye[2] * to_eye[2]);
            for (int a = 0; a < 3; ++a) p.S[a] = to_eye[a] * inv;
        } else {
            for (int a = 0; a < 3; ++a) p.S[a] = lanes(f.camera.w[a]);
        }
        Lane8f shaded[3];
        shade_lanes(p, lighting, active, shaded);
        const Lane8i mask = lane_mask(active);
        for (int a = 0; a < 3; ++a) I[a] = lane_select(mask, shaded[a], I[a]);
        stats.samples += static_cast<uint64_t>(lane_count(active));
    }
    store_colours(out, I[0], I[1], I[2]);
    for (unsigned rest = covered & ~active; rest; rest &= rest - 1) {
        const int k = __builtin_ctz(rest);
        out[k] = shade_fragment(f, lighting, frags[k], stats);
    }
}

/// The same fragment's colour with its terms (docs/SCENES.md#terms; `tests`: the point's depth
/// tests). Its colour has the bits shade_fragment() gives.
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
