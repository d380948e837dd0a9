// RayTreeRecorder: the observer of trace() that records a RayTree (luz/ray_tree.h) node by node
// while it runs, with the very numbers shade() and trace() used.
#pragma once

#include <vector>

#include "geometry/hit.h"
#include "geometry/scene.h"
#include "luz/ray_tree.h"
#include "math/vec3.h"
#include "render/recursion.h"
#include "shading/shade.h"

namespace luz {

/// The observer of trace() (render/whitted.h) that records its rays into a RayTree, node by
/// node, as they are traced; beyond kRayTreeMaxNodes nodes it stops (RayTree::truncated).
class RayTreeRecorder {
  public:
    RayTreeRecorder(RayTree& tree, size_t lights) : tree_(tree), lights_(lights) {}

    void ray(const Ray& ray, int depth);
    void found(float t, RayHit hit, int light);
    ShadeTerms* terms();
    void shaded(const Hit& hit, int material, const SurfacePoint& sp, const ShadeTerms* terms,
                const Rgb& local);
    void bounced(const Bounce& b);
    void secondary(RayKind kind, float coefficient, const Rgb& returned, float A,
                   const Rgb& contribution);
    Rgb done(const Rgb& c);

  private:
    RayTree& tree_;
    size_t lights_;
    std::vector<int> open_;  ///< the nodes of the rays being traced, innermost last (−1: cut)
    int last_ = -1;          ///< the node of the ray that finished last
    ShadeTerms terms_;
};

/// The ray tree of the primary ray through pixel-space point (px, py) — pixel (i, j)'s centre
/// is (i + 0.5, j + 0.5) — traced by the scene's ray pipeline (Whitted::trace observed by a
/// RayTreeRecorder). A zbuffer scene is traced as raycast (max depth 0, no shadow rays), which
/// gives the zbuffer's colour up to tessellation (docs/SCENES.md#models). nodes[0].colour is the
/// sample's colour.
RayTree trace_ray_tree(const BuiltScene& scene, const Settings& settings, float px, float py);

}  // namespace luz
