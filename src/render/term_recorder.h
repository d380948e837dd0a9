// TermRecorder: the observer of trace() (render/whitted.h) that keeps a camera ray's terms
// (docs/SCENES.md#terms) as they are computed at its primary hit; the rays below it are not
// observed.
#pragma once

#include <span>
#include <vector>

#include "geometry/hit.h"
#include "render/aov.h"
#include "render/ray_tree.h"
#include "render/recursion.h"
#include "shading/shade.h"

namespace luz {

class TermRecorder {
  public:
    TermRecorder(TermSample& out, size_t lights) : out_(out), lights_(lights) {}

    void ray(const Ray&, int) { ++level_; }
    void found(float t, RayHit hit, int) {
        if (level_ != 1) return;
        out_.depth = t;  // +inf on a miss
        object_ = hit == RayHit::object;
    }
    ShadeTerms* terms() {
        if (level_ != 1) return nullptr;
        thread_local std::vector<LightTerm> scratch;  // no allocation per sample
        scratch.assign(lights_, LightTerm{});
        terms_.light = scratch;
        return &terms_;
    }
    void shaded(const Hit&, int, const SurfacePoint& sp, const ShadeTerms* terms, const Rgb&) {
        if (level_ != 1) return;
        out_.ambient = terms->ambient;
        for (const LightTerm& t : terms->light) {
            out_.diffuse += t.diffuse;
            out_.specular += t.specular;
            out_.shadow += t.unshadowed * (1.0f - t.visibility);  // (1 − vis_j)·(…with vis_j = 1)
        }
        out_.normal = terms->flipped ? -sp.N : sp.N;
    }
    void bounced(const Bounce&) {}
    void secondary(RayKind kind, float, const Rgb&, float, const Rgb& contribution) {
        if (level_ != 1) return;
        (kind == RayKind::reflection ? out_.reflected : out_.refracted) = contribution;
    }
    Rgb done(const Rgb& c) {
        if (level_-- == 1 && !object_) out_.emitted = c;  // the background or a light's colour
        return c;
    }

  private:
    TermSample& out_;
    size_t lights_;
    int level_ = 0;  ///< the depth of the ray being traced, + 1 (0: none)
    bool object_ = false;
    ShadeTerms terms_;
};

}  // namespace luz
