// BuiltScene queries by the scene's BVH (render.accel = bvh): bounded shapes and mesh triangles in
// the 8-wide BVH, its leaves' primitives tested four at a time, planes tested apart; ties
// resolved by Best, crossings counted by material. A BVH that is one leaf (BuiltScene::root_leaf)
// is tested without the node loop.
#include "geometry/query_parts.h"

namespace luz::query {

bool nearest_hit_bvh(const BuiltScene& scene, const Ray& r, float t_min, float t_max, Hit& hit,
                     IntersectCounters& counters) {
    Best best(t_max);
    offer_unbounded(scene, r, t_min, best, counters);
    LazyWatertight w;
    const auto leaf = [&](uint32_t first, uint32_t count) {
        for_each_block(scene, first, count, [&](const PrimBlock& b, unsigned lanes) {
            offer_block(scene, b, lanes, r, w.for_block(r, b, lanes), t_min, best, counters);
            return true;
        });
    };
    if (scene.root_leaf != 0) {
        leaf(0, scene.root_leaf);
    } else {
        float limit = best.t;
        scene.bvh.nearest_leaves(r, t_min, limit, counters.bounds,
                                 [&](uint32_t first, uint32_t count, float& node_limit) {
                                     leaf(first, count);
                                     node_limit = best.t;
                                 });
    }
    if (best.found) hit = best.hit;
    return best.found;
}

float transmittance_bvh(const BuiltScene& scene, const Materials& materials, const Ray& r,
                        float t_min, float t_max, IntersectCounters& counters, ShadowCache* cache) {
    Crossings crossings;
    for (uint32_t i : scene.unbounded) {
        if (!cross_shape(scene, materials, i, r, t_min, t_max, crossings, counters)) return 0.0f;
    }
    LazyWatertight w;
    if (cache != nullptr && cache->lanes != 0) {
        // The last occluder first: if it blocks, so would the traversal's find; its transparent
        // crossings (the other lanes') are the traversal's to count, hence counted apart.
        Crossings apart;
        const PrimBlock& b = scene.bvh_blocks[cache->block];
        if (!cross_block(scene, materials, b, cache->lanes, r, w.for_block(r, b, cache->lanes),
                         t_min, t_max, apart, counters))
            return 0.0f;
    }
    // whether the leaf of slots first … first + count − 1 blocks r
    const auto blocks = [&](uint32_t first, uint32_t count) {
        return !for_each_block(scene, first, count, [&](const PrimBlock& b, unsigned lanes) {
            if (cross_block(scene, materials, b, lanes, r, w.for_block(r, b, lanes), t_min, t_max,
                            crossings, counters))
                return true;
            if (cache != nullptr) {
                cache->block = static_cast<uint32_t>(&b - scene.bvh_blocks.data());
                cache->lanes = lanes;
            }
            return false;
        });
    };
    const bool blocked = scene.root_leaf != 0
                             ? blocks(0, scene.root_leaf)
                             : scene.bvh.any_leaves(r, t_min, t_max, counters.bounds, blocks);
    if (!blocked && cache != nullptr) cache->lanes = 0;
    if (blocked) return 0.0f;
    return crossings.lost() ? transmittance_all(scene, materials, r, t_min, t_max, counters)
                            : crossings.product();
}

}  // namespace luz::query
