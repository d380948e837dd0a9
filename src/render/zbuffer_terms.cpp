// The zbuffer's per-term samples (docs/SCENES.md#terms): a fragment's colour split into the terms
// shade() computed — ambient, diffuse, specular, emitted — with its depth, normal and depth tests.
#include <cmath>
#include <limits>
#include <vector>

#include "render/zbuffer_shade.h"

namespace luz {

TermSample shade_fragment_terms(const ZbufferFrame& f, const Lighting& lighting,
                                const Fragment& frag, uint32_t tests, RenderStats& stats) {
    const Settings& desc = f.settings;
    TermSample s;
    s.tests = static_cast<float>(tests);
    if (frag.triangle == kNoTriangle) {  // the background
        s.colour = s.emitted = desc.image.background;
        s.depth = std::numeric_limits<float>::infinity();
        return s;
    }
    const int32_t material = f.geometry.triangle_material[frag.triangle];
    // The distance t along the unit camera ray: along −w (orthographic) or from the eye.
    auto ray_distance = [&](const Vec3& P) {
        return f.perspective ? length(P - f.camera.position) : f.camera.to_view(P).z;
    };
    if (material < 0) {  // a visible light sphere: the light's clamped colour
        s.colour = s.emitted = clamp01(desc.lights[-1 - material].intensity);
        const TriangleMesh& mesh = f.geometry.mesh;
        const uint32_t* idx = &mesh.indices[3 * static_cast<size_t>(frag.triangle)];
        const float b0 = 1.0f - frag.b1 - frag.b2;
        s.depth = ray_distance(mesh.positions[idx[0]] * b0 + mesh.positions[idx[1]] * frag.b1 +
                               mesh.positions[idx[2]] * frag.b2);
        return s;
    }
    ++stats.samples;
    const ShadingPoint p = fragment_point(f, frag, material);
    thread_local std::vector<LightTerm> lights;
    lights.assign(lighting.lights.size(), LightTerm{});
    ShadeTerms terms;
    terms.light = lights;
    s.colour = shade(p, lighting, AllVisible{}, &terms);
    s.ambient = terms.ambient;
    for (const LightTerm& t : lights) {
        s.diffuse += t.diffuse;
        s.specular += t.specular;
    }
    s.normal = terms.flipped ? -p.N : p.N;
    s.depth = ray_distance(p.P);
    return s;
}

}  // namespace luz
