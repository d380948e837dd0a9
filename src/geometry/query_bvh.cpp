// BuiltScene queries by the scene's BVH (render.accel = bvh): bounded shapes and mesh triangles in
// the 8-wide BVH, its leaves' triangles tested four at a time, planes tested apart; ties
// resolved by Best, crossings counted by material.
#include "geometry/query_parts.h"

namespace luz::query {

bool nearest_hit_bvh(const BuiltScene& scene, const Ray& r, float t_min, float t_max, Hit& hit,
                     IntersectCounters& counters) {
    Best best(t_max);
    for (uint32_t i : scene.unbounded) offer_shape(scene, i, r, t_min, best, counters);
    const WatertightRay w = scene.mesh_triangles ? prepare_watertight(r) : WatertightRay{};
    float limit = best.t;
    scene.bvh.nearest_leaves(
        r, t_min, limit, counters.bounds, [&](uint32_t first, uint32_t count, float& node_limit) {
            for_each_block(scene, first, count, [&](const PrimBlock& b, unsigned lanes) {
                offer_block(scene, b, lanes, r, w, t_min, best, counters);
                return true;
            });
            node_limit = best.t;
        });
    if (best.found) hit = best.hit;
    return best.found;
}

float transmittance_bvh(const BuiltScene& scene, const Materials& materials, const Ray& r,
                        float t_min, float t_max, IntersectCounters& counters) {
    Crossings crossings;
    for (uint32_t i : scene.unbounded) {
        if (!cross_shape(scene, materials, i, r, t_min, t_max, crossings, counters)) return 0.0f;
    }
    const WatertightRay w = scene.mesh_triangles ? prepare_watertight(r) : WatertightRay{};
    const bool blocked =
        scene.bvh.any_leaves(r, t_min, t_max, counters.bounds, [&](uint32_t first, uint32_t count) {
            return !for_each_block(scene, first, count, [&](const PrimBlock& b, unsigned lanes) {
                return cross_block(scene, materials, b, lanes, r, w, t_min, t_max, crossings,
                                   counters);
            });
        });
    return blocked ? 0.0f : crossings.product();
}

}  // namespace luz::query
