// RayTree: what trace() did for one primary ray, recorded node by node while it ran (the very
// numbers shade() and trace() used), for the viewer's ray-tree inspector and its tests.
#pragma once

#include <vector>

#include "geometry/hit.h"
#include "geometry/scene.h"
#include "math/vec3.h"
#include "render/recursion.h"
#include "shading/shade.h"

namespace luz {

enum class RayKind { primary, reflection, refraction };
enum class RayHit { background, light, object };

/// One traced ray: where it went, what it hit, the terms of the local model there, and how its
/// children's colours were weighted into its own.
struct RayTreeNode {
    RayKind kind = RayKind::primary;
    int depth = 0;
    int parent = -1;  ///< index of the parent node, −1 for the primary ray
    Vec3 origin, direction;
    RayHit hit = RayHit::background;
    int object = -1;                ///< index into SceneDesc::objects (hit == object)
    int material = -1;              ///< index into SceneDesc::materials (hit == object)
    int light = -1;                 ///< index into SceneDesc::lights (hit == light)
    float t = 0;                    ///< distance along the ray (infinity on a miss)
    Vec3 P, N;                      ///< hit point and shading normal (before the two-sided flip)
    Rgb ambient;                    ///< Ia·Ka
    std::vector<LightTerm> lights;  ///< per light: visibility, cosθ, cosα, diffuse, specular
    bool flipped = false;           ///< N was flipped towards the viewer
    Rgb local;                      ///< shade()'s colour: ambient + Σ (diffuse + specular)
    bool total_internal_reflection = false;  ///< the refracted share followed the reflection
    /// As a child: the colour trace() returned for this ray, A (1, 1/(d+K) or 1/d²), the
    /// coefficient (reflection or transparency) and the contribution added to the parent:
    /// returned·A·coefficient.
    Rgb returned;
    float A = 1, coefficient = 1;
    Rgb contribution;
    int reflection_child = -1, refraction_child = -1;
    Rgb color;  ///< the node's total: local + the children's contributions
};

/// The nodes of one primary ray's tree, parents before children (nodes[0] is the primary).
/// The most nodes a recorded ray tree keeps: an exploding tree (2^depth rays) is cut there.
inline constexpr size_t kRayTreeMaxNodes = 20000;

struct RayTree {
    std::vector<RayTreeNode> nodes;
    bool truncated = false;  ///< more rays were traced than kRayTreeMaxNodes: recording stopped
    bool raycast_for_zbuffer = false;  ///< the scene's pipeline is zbuffer: traced as raycast
};

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
/// gives the zbuffer's colour up to tessellation (SPEC §1). nodes[0].color is the sample's colour.
RayTree trace_ray_tree(const BuiltScene& scene, const Settings& settings, float px, float py);

}  // namespace luz
