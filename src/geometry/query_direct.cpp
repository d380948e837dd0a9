// BuiltScene queries for a small scene without meshes (BuiltScene::direct: at most 8 shapes, which
// one 8-wide BVH node would hold): every shape in scene order, its world-form spheres four at a
// time (sphere_group.h), the other shapes behind their box unless they have a world form.
#include "geometry/query_parts.h"

namespace luz::query {

namespace {

/// The roots of r with every sphere group of a direct scene, at once.
struct GroupRoots {
    SphereGroupRoots group[BuiltScene::kDirectShapes / SphereGroup::kLanes];
    GroupRoots(const BuiltScene& scene, const Ray& r) {
        for (size_t g = 0; g < scene.sphere_groups.size(); ++g)
            group[g] = sphere_group_roots(scene.sphere_groups[g], r);
    }
    /// The answer of sphere lane `lane` (BuiltScene::sphere_lane): whether it hits, and its roots;
    /// false if the lane needs the scalar test (its double path) instead.
    bool answer(int lane, bool& hit, float& t0, float& t1) const {
        const SphereGroupRoots& g = group[lane / SphereGroup::kLanes];
        const int k = lane % SphereGroup::kLanes;
        if (g.slow & (1u << k)) return false;
        hit = (g.hit & (1u << k)) != 0;
        t0 = g.t0[k];
        t1 = g.t1[k];
        return true;
    }
};

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

}  // namespace

void prepare_direct(BuiltScene& scene) {
    scene.direct = scene.mesh_triangles == 0 && scene.shapes.size() <= BuiltScene::kDirectShapes;
    scene.sphere_groups.clear();
    scene.sphere_lane.assign(scene.shapes.size(), -1);
    for (size_t i = 0; i < scene.shapes.size() && scene.direct; ++i) {
        const Shape& s = scene.shapes[i];
        if (s.world_form && s.type == ShapeType::sphere) {
            scene.sphere_lane[i] = add_to_sphere_groups(scene.sphere_groups, s);
        }
    }
}

/// The nearest hit needs no tie rule of its own: a later shape must be strictly nearer to
/// replace an earlier one, so ties keep the lowest shape.
bool nearest_hit_direct(const BuiltScene& scene, const Ray& r, float t_min, float t_max, Hit& hit,
                        IntersectCounters& counters) {
    const GroupRoots roots(scene, r);
    LazyBoxTest boxes{r};
    int nearest = -1;
    Hit best;
    for (size_t k = 0; k < scene.shapes.size(); ++k) {
        const Shape& s = scene.shapes[k];
        bool met;
        float t0, t1, t;
        if (const int lane = scene.sphere_lane[k]; lane >= 0 && roots.answer(lane, met, t0, t1)) {
            ++counters.primitive;
            if (met && nearest_root(t0, t1, t_min, t_max, t)) {  // as intersect() chooses
                best = Hit{};
                best.t = t_max = t;
                nearest = static_cast<int>(k);
            }
            continue;
        }
        if (!s.world_form && is_bounded(s) &&
            !boxes.hit(scene.bounds[k], t_min, bvh_detail::with_margin(t_max), counters))
            continue;
        ++counters.primitive;
        Hit h;
        if (intersect(s, r, t_min, t_max, h)) {
            best = h;
            t_max = h.t;
            nearest = static_cast<int>(k);
        }
    }
    if (nearest < 0) return false;
    hit = best;
    hit.shape = nearest;
    return true;
}

float transmittance_direct(const BuiltScene& scene, const Materials& materials, const Ray& r,
                           float t_min, float t_max, IntersectCounters& counters) {
    const GroupRoots roots(scene, r);
    LazyBoxTest boxes{r};
    Crossings crossings;
    for (size_t k = 0; k < scene.shapes.size(); ++k) {
        const Shape& s = scene.shapes[k];
        const uint32_t i = static_cast<uint32_t>(k);
        bool met;
        float t0, t1;
        if (const int lane = scene.sphere_lane[k]; lane >= 0 && roots.answer(lane, met, t0, t1)) {
            ++counters.primitive;  // as count_crossings() counts
            const uint32_t n = met ? roots_within(t0, t1, t_min, t_max) : 0;
            if (n > 0 && !add_crossings(materials, s.material, n, crossings)) return 0.0f;
            continue;
        }
        if (!s.world_form && is_bounded(s) && !boxes.hit(scene.bounds[k], t_min, t_max, counters))
            continue;
        if (!cross_shape(scene, materials, i, r, t_min, t_max, crossings, counters)) return 0.0f;
    }
    return crossings.product();
}

}  // namespace luz::query
