// BuiltScene queries that test everything (render.accel = none): every shape in scene order behind
// its bounds, every mesh triangle; the same tie rule as the BVH, so the same answers.
#include "geometry/query_parts.h"

namespace luz::query {

bool nearest_hit_all(const BuiltScene& scene, const Ray& r, float t_min, float t_max, Hit& hit,
                     IntersectCounters& counters) {
    Best best(t_max);
    const Vec3 inv_dir = inverse_direction(r.direction);
    const WatertightRay w = scene.mesh_triangles ? prepare_watertight(r) : WatertightRay{};
    for (size_t k = 0; k < scene.shapes.size(); ++k) {
        const Shape& s = scene.shapes[k];
        const uint32_t i = static_cast<uint32_t>(k);
        if (is_bounded(s)) {
            ++counters.bounds;
            if (!hit_bounds(scene.bounds[k], r, inv_dir, t_min, bvh_detail::with_margin(best.t)))
                continue;
        }
        if (!s.mesh) {
            offer_shape(scene, i, r, t_min, best, counters);
            continue;
        }
        Vec3 p0, p1, p2;
        for (size_t t = 0; t < s.mesh->triangle_count(); ++t) {
            s.mesh->vertices(t, p0, p1, p2);
            offer_triangle(w, p0, p1, p2, i, static_cast<uint32_t>(t), t_min, best, counters);
        }
    }
    if (best.found) hit = best.hit;
    return best.found;
}

float transmittance_all(const BuiltScene& scene, const Materials& materials, const Ray& r,
                        float t_min, float t_max, IntersectCounters& counters) {
    const Vec3 inv_dir = inverse_direction(r.direction);
    const WatertightRay w = scene.mesh_triangles ? prepare_watertight(r) : WatertightRay{};
    Crossings crossings;
    for (size_t k = 0; k < scene.shapes.size(); ++k) {
        const Shape& s = scene.shapes[k];
        const uint32_t i = static_cast<uint32_t>(k);
        if (is_bounded(s)) {
            ++counters.bounds;
            if (!hit_bounds(scene.bounds[k], r, inv_dir, t_min, t_max)) continue;
        }
        if (!s.mesh) {
            if (!cross_shape(scene, materials, i, r, t_min, t_max, crossings, counters))
                return 0.0f;
            continue;
        }
        Vec3 p0, p1, p2;
        for (size_t t = 0; t < s.mesh->triangle_count(); ++t) {
            s.mesh->vertices(t, p0, p1, p2);
            if (!cross_triangle(scene, materials, w, p0, p1, p2, i, static_cast<uint32_t>(t), t_min,
                                t_max, crossings, counters))
                return 0.0f;
        }
    }
    return crossings.product();
}

}  // namespace luz::query
