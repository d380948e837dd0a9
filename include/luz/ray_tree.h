// RayTree: what trace() did for one primary ray, node by node (the very numbers shade() and
// trace() used), for the viewer's ray-tree inspector, luz.ray_tree and their tests.
#pragma once

#include <cstddef>
#include <vector>

#include "luz/vec3.h"

namespace luz {

/// One light's share at a point: vis · (diffuse + specular) is what it adds.
struct LightTerm {
    float visibility = 1;  ///< vis_j: 1 lit, 0 blocked, transparency product in between
    float distance = 0;    ///< d_j
    float cos_theta = 0;   ///< max(0, N·L_j)
    float cos_alpha = 0;   ///< max(0, R_j·S), 0 when N·L_j ≤ 0
    Rgb diffuse;  ///< vis_j·Il_j·Kd·cosθ_j (lambert) or vis_j·Il_j/(d_j+K)·Kd·cosθ_j (phong)
    Rgb specular;  ///< vis_j·Il_j/(d_j+K)·Ks·cosα_j^n (phong only); (d_j+K): the law's divisor
    Rgb unshadowed;  ///< diffuse + specular as they would be with vis_j = 1 (docs/SCENES.md#terms
                     ///< shadow)
};

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
    Rgb colour;  ///< the node's total: local + the children's contributions
};

/// The nodes of one primary ray's tree, parents before children (nodes[0] is the primary).
/// The most nodes a recorded ray tree keeps: an exploding tree (2^depth rays) is cut there.
inline constexpr size_t kRayTreeMaxNodes = 20000;

struct RayTree {
    std::vector<RayTreeNode> nodes;
    bool truncated = false;  ///< more rays were traced than kRayTreeMaxNodes: recording stopped
    bool raycast_for_zbuffer = false;  ///< the scene's pipeline is zbuffer: traced as raycast
};

}  // namespace luz
