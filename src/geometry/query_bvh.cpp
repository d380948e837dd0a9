// BuiltScene queries by the scene's BVH (render.accel = bvh): bounded shapes and mesh triangles in
// the 8-wide BVH, planes tested apart; ties resolved by Best, crossings counted by material.
#include "geometry/query_parts.h"

namespace luz::query {

bool nearest_hit_bvh(const BuiltScene& scene, const Ray& r, float t_min, float t_max, Hit& hit,
                     IntersectCounters& counters) {
    Best best(t_max);
    for (uint32_t i : scene.unbounded) offer_shape(scene, i, r, t_min, best, counters);
    const WatertightRay w = scene.mesh_triangles ? prepare_watertight(r) : WatertightRay{};
    float limit = best.t;
    scene.bvh.nearest(r, t_min, limit, counters.bounds, [&](uint32_t slot, float& node_limit) {
        const BvhPrim& p = scene.bvh_prims[slot];
        if (p.triangle != BvhPrim::kNotTriangle) {
            offer_triangle(w, p.p0, p.p1, p.p2, p.shape, p.triangle, t_min, best, counters);
        } else {
            offer_shape(scene, p.shape, r, t_min, best, counters);
        }
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
    const bool blocked = scene.bvh.any(r, t_min, t_max, counters.bounds, [&](uint32_t slot) {
        const BvhPrim& p = scene.bvh_prims[slot];
        if (p.triangle != BvhPrim::kNotTriangle) {
            return !cross_triangle(scene, materials, w, p.p0, p.p1, p.p2, p.shape, p.triangle,
                                   t_min, t_max, crossings, counters);
        }
        return !cross_shape(scene, materials, p.shape, r, t_min, t_max, crossings, counters);
    });
    return blocked ? 0.0f : crossings.product();
}

}  // namespace luz::query
