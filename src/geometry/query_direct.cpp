// BuiltScene queries for a small scene without meshes (BuiltScene::direct: at most 8 shapes, which
// one 8-wide BVH node would hold): its world-form spheres four at a time (sphere_group.h), then
// its world-form planes, then the other shapes behind their boxes. The nearest hit is ordered by
// (t, shape) as everywhere (query_parts.h: Best), so the order of the tests changes no answer;
// nor does it change a transmittance (crossings multiply in material order, and an opaque one is
// 0 wherever it is met).
#include "geometry/query_parts.h"

namespace luz::query {

namespace {

/// Box tests of one ray, its inverse direction computed at the first.
struct LazyBoxTest {
    const Ray& r;
    Vec3 inv_dir{0.0f};
    bool ready = false;
    bool hit(const Bounds3& b, float t_min, float t_max, IntersectCounters& counters) {
        if (!ready) inv_dir = inverse_direction(r.direction);
        ready = true;
        ++counters.bounds;
        return hit_bounds(b, r, inv_dir, t_min, t_max);
    }
};

/// The lanes of group g in use.
unsigned used_lanes(const SphereGroup& g) { return (1u << g.count) - 1; }

}  // namespace

void prepare_direct(BuiltScene& scene) {
    scene.direct = scene.mesh_triangles == 0 && scene.shapes.size() <= BuiltScene::kDirectShapes;
    scene.sphere_groups.clear();
    scene.direct_planes.clear();
    scene.direct_others.clear();
    for (size_t i = 0; i < scene.shapes.size() && scene.direct; ++i) {
        const Shape& s = scene.shapes[i];
        const uint32_t index = static_cast<uint32_t>(i);
        if (s.world_form && s.type == ShapeType::sphere) {
            const int lane = add_to_sphere_groups(scene.sphere_groups, s);
            scene.sphere_groups.back().shape[lane % SphereGroup::kLanes] = index;
        } else if (s.world_form && s.type == ShapeType::plane) {
            scene.direct_planes.push_back(index);
        } else {
            scene.direct_others.push_back(index);
        }
    }
}

bool nearest_hit_direct(const BuiltScene& scene, const Ray& r, float t_min, float t_max, Hit& hit,
                        IntersectCounters& counters) {
    Best best(t_max);
    for (const SphereGroup& g : scene.sphere_groups) {
        const SphereGroupRoots q = sphere_group_roots(g, r);
        counters.primitive += static_cast<uint64_t>(lane_count(used_lanes(g) & ~q.slow));
        for (unsigned lanes = q.hit; lanes != 0; lanes &= lanes - 1) {
            const int k = __builtin_ctz(lanes);
            float t;  // the root intersect() would choose
            if (nearest_root(q.t0[k], q.t1[k], t_min, best.limit(), t) &&
                best.better(t, g.shape[k], 0))
                best.take(t, g.shape[k], 0, 0.0f, 0.0f, part_side);
        }
        for (unsigned lanes = q.slow; lanes != 0; lanes &= lanes - 1)
            offer_shape(scene, g.shape[__builtin_ctz(lanes)], r, t_min, best, counters);
    }
    for (const uint32_t i : scene.direct_planes) {
        ++counters.primitive;
        const float t = shapes::plane::world_root(scene.shapes[i], r);  // as intersect() finds it
        if (t > t_min && t < best.limit() && best.better(t, i, 0))
            best.take(t, i, 0, 0.0f, 0.0f, part_side);
    }
    LazyBoxTest boxes{r};
    for (const uint32_t i : scene.direct_others) {
        const Shape& s = scene.shapes[i];
        if (is_bounded(s) &&
            !boxes.hit(scene.bounds[i], t_min, bvh_detail::with_margin(best.limit()), counters))
            continue;
        offer_shape(scene, i, r, t_min, best, counters);
    }
    if (!best.found) return false;
    hit = best.hit;
    return true;
}

float transmittance_direct(const BuiltScene& scene, const Materials& materials, const Ray& r,
                           float t_min, float t_max, IntersectCounters& counters) {
    Crossings crossings;
    for (const SphereGroup& g : scene.sphere_groups) {
        const SphereGroupRoots q = sphere_group_roots(g, r);
        counters.primitive += static_cast<uint64_t>(lane_count(used_lanes(g) & ~q.slow));
        for (unsigned lanes = q.hit; lanes != 0; lanes &= lanes - 1) {
            const int k = __builtin_ctz(lanes);
            const uint32_t n = roots_within(q.t0[k], q.t1[k], t_min, t_max);
            if (n > 0 && !add_crossings(materials, scene.shapes[g.shape[k]].material, n, crossings))
                return 0.0f;
        }
        for (unsigned lanes = q.slow; lanes != 0; lanes &= lanes - 1) {
            if (!cross_shape(scene, materials, g.shape[__builtin_ctz(lanes)], r, t_min, t_max,
                             crossings, counters))
                return 0.0f;
        }
    }
    for (const uint32_t i : scene.direct_planes) {
        ++counters.primitive;
        const float t = shapes::plane::world_root(scene.shapes[i], r);  // one root, or none (NaN)
        if (t > t_min && t < t_max &&
            !add_crossings(materials, scene.shapes[i].material, 1, crossings))
            return 0.0f;
    }
    LazyBoxTest boxes{r};
    for (const uint32_t i : scene.direct_others) {
        const Shape& s = scene.shapes[i];
        if (is_bounded(s) && !boxes.hit(scene.bounds[i], t_min, t_max, counters)) continue;
        if (!cross_shape(scene, materials, i, r, t_min, t_max, crossings, counters)) return 0.0f;
    }
    return crossings.product();
}

}  // namespace luz::query
