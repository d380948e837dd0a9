// BuiltScene: the runtime scene built once from a SceneDesc; it never changes while rendering.
#pragma once

#include <cstdint>
#include <vector>

#include "geometry/prim_block.h"
#include "geometry/shape.h"
#include "geometry/wide_bvh.h"
#include "math/huge_pages.h"
#include "scene/scene_desc.h"

namespace luz {

/// A primitive of the scene's BVH: a bounded shape, or one triangle of a mesh shape with its
/// world vertices (kept in the scene's blocks, so that a leaf's triangles lie together).
struct BvhPrim {
    Vec3 p0, p1, p2;    ///< the triangle's vertices (mesh triangles only)
    uint32_t shape;     ///< index into BuiltScene::shapes
    uint32_t triangle;  ///< the mesh's triangle, or kNotTriangle for a whole shape

    static constexpr uint32_t kNotTriangle = PrimBlock::kNotTriangle;
};

/// The scene's geometry as a render needs it: shapes, bounds, BVH. Settings (camera, lights,
/// material constants …) are not part of it: they are given to each render.
struct BuiltScene {
    GeometryDesc geometry;        ///< tessellation and accel, as built
    size_t material_count = 0;    ///< materials the objects may refer to (SceneDesc::materials)
    std::vector<Shape> shapes;    ///< one per object, in the scene's order
    std::vector<Bounds3> bounds;  ///< world bounds of each shape (infinite for planes)
    uint64_t mesh_triangles = 0;  ///< triangles in all meshes

    // Ray queries (scene_query.h). The BVH holds every bounded shape and every mesh triangle;
    // unbounded shapes (planes) are tested apart. Built by build_bvh(): binned SAH counting
    // blocks of four, collapsed to 8-wide nodes (wide_bvh.h).
    Bvh8 bvh;
    /// The BVH's primitives: slot s is lane s % 4 of block s / 4; each leaf starts a block
    /// (the lanes after its end are padding). On huge pages when large (huge_pages.h).
    HugeVector<PrimBlock> bvh_blocks;
    std::vector<uint32_t> unbounded;  ///< shapes outside the BVH (planes), in scene order
    bool has_bvh = false;  ///< build_bvh() ran: with render.accel bvh, queries use the BVH
    /// When the whole BVH is one leaf (its root node's only child: a scene of a few bounded
    /// shapes), its slot count (the slots 0 … root_leaf − 1); else 0. The queries then test that
    /// leaf without the node loop.
    uint32_t root_leaf = 0;
    double bvh_build_seconds = 0;

    /// The primitive in slot s of the BVH (a sphere lane as a whole shape: its corners are
    /// meaningless).
    BvhPrim bvh_prim(uint32_t s) const {
        const PrimBlock& b = bvh_blocks[s / PrimBlock::kLanes];
        const int k = static_cast<int>(s % PrimBlock::kLanes);
        const bool shape = b.triangle[k] == PrimBlock::kSphere ||
                           b.triangle[k] == PrimBlock::kAroundAxis ||
                           b.triangle[k] == PrimBlock::kCylinder;
        const uint32_t tri = shape ? BvhPrim::kNotTriangle : b.triangle[k];
        return {b.corner(0, k), b.corner(1, k), b.corner(2, k), b.shape[k], tri};
    }
    /// Bytes held by the BVH: nodes and primitives (the leaf order is not kept).
    size_t bvh_bytes() const {
        return bvh.memory_bytes() + bvh_blocks.capacity() * sizeof(PrimBlock) +
               unbounded.capacity() * sizeof(uint32_t);
    }
};

/// Builds the runtime scene from a validated description. The BVH is built when the scene's
/// rays will use it: `render.accel` is bvh and the pipeline is raycast or raytrace (otherwise
/// build_bvh() may be called later, before a ray pipeline renders it).
BuiltScene build_scene(const SceneDesc& desc);
/// The same, the BVH built only if `with_bvh` (and `render.accel` is bvh).
BuiltScene build_scene(const SceneDesc& desc, bool with_bvh);

/// (Re)builds scene.bvh over the scene's shapes and mesh triangles (binned SAH, bvh.h, then
/// 8-wide, wide_bvh.h), sets root_leaf, and times it in bvh_build_seconds.
void build_bvh(BuiltScene& scene);

}  // namespace luz
