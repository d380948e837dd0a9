// BuiltScene ray queries: BVH traversal (render.accel = bvh), every shape in order for a small
// scene without meshes (bvh, BuiltScene::direct), or every shape and triangle in order (none), with
// one rule for ties so all give the same answers.
#include "geometry/scene_query.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "math/next_float.h"

namespace luz {

bool hit_bounds(const Bounds3& b, const Ray& r, const Vec3& inv_dir, float t_min, float t_max) {
    for (int a = 0; a < 3; ++a) {
        float t0 = (b.lo[a] - r.origin[a]) * inv_dir[a];
        float t1 = (b.hi[a] - r.origin[a]) * inv_dir[a];
        if (t0 > t1) std::swap(t0, t1);
        // NaN (0·∞ for a ray in a slab's plane) leaves the interval unchanged.
        t_min = t0 > t_min ? t0 : t_min;
        t_max = t1 < t_max ? t1 : t_max;
        if (t_min > t_max) return false;
    }
    return true;
}

namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

Vec3 inverse_direction(const Vec3& d) { return {1.0f / d.x, 1.0f / d.y, 1.0f / d.z}; }

/// A small scene without meshes (BuiltScene::direct): tested shape by shape, even with a BVH.
bool use_direct(const BuiltScene& scene) {
    return scene.direct && scene.geometry.accel == Accel::bvh;
}

bool use_bvh(const BuiltScene& scene) {
    return scene.has_bvh && scene.geometry.accel == Accel::bvh;
}

/// The nearest hit so far, ordered by (t, shape, triangle): whatever order primitives are
/// tested in, the lowest of these wins.
struct Best {
    explicit Best(float t_max) : t(t_max) {}
    float t;  // t_max until something is found
    uint32_t shape = 0, triangle = 0;
    bool found = false;
    Hit hit;

    /// The t_max for a primitive test: ties with the best must still be reported.
    float limit() const { return found ? next_up(t) : t; }
    bool better(float t2, uint32_t s, uint32_t tri) const {
        return !found || t2 < t || (t2 == t && (s < shape || (s == shape && tri < triangle)));
    }
    void take(float t2, uint32_t s, uint32_t tri, float u, float v, int part) {
        t = t2;
        shape = s;
        triangle = tri;
        found = true;
        hit.t = t2;
        hit.shape = static_cast<int>(s);
        hit.u = u;
        hit.v = v;
        hit.part = part;
    }
};

/// Shape i (not a mesh) against r.
void offer_shape(const BuiltScene& scene, uint32_t i, const Ray& r, float t_min, Best& best,
                 IntersectCounters& counters) {
    ++counters.primitive;
    Hit h;
    if (intersect(scene.shapes[i], r, t_min, best.limit(), h) && best.better(h.t, i, 0)) {
        best.take(h.t, i, 0, h.u, h.v, h.part);
    }
}

/// Triangle `tri` of shape i, vertices p0, p1, p2, against r.
void offer_triangle(const WatertightRay& w, const Vec3& p0, const Vec3& p1, const Vec3& p2,
                    uint32_t i, uint32_t tri, float t_min, Best& best,
                    IntersectCounters& counters) {
    ++counters.primitive;
    float t, b1, b2;
    if (intersect_triangle(w, p0, p1, p2, t_min, best.limit(), t, b1, b2) &&
        best.better(t, i, tri)) {
        best.take(t, i, tri, b1, b2, static_cast<int>(tri));
    }
}

bool nearest_bvh(const BuiltScene& scene, const Ray& r, float t_min, Best& best,
                 IntersectCounters& counters) {
    for (uint32_t i : scene.unbounded) offer_shape(scene, i, r, t_min, best, counters);
    const WatertightRay w = scene.mesh_triangles ? prepare_watertight(r) : WatertightRay{};
    float t_max = best.t;
    scene.bvh.nearest(r, t_min, t_max, counters.bounds, [&](uint32_t slot, float& limit) {
        const BvhPrim& p = scene.bvh_prims[slot];
        if (p.triangle != BvhPrim::kNotTriangle) {
            offer_triangle(w, p.p0, p.p1, p.p2, p.shape, p.triangle, t_min, best, counters);
        } else {
            offer_shape(scene, p.shape, r, t_min, best, counters);
        }
        limit = best.t;
    });
    return best.found;
}

bool nearest_all(const BuiltScene& scene, const Ray& r, float t_min, Best& best,
                 IntersectCounters& counters) {
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
    return best.found;
}

/// Transparent crossings counted per material; their product is taken in material order.
class Crossings {
  public:
    void add(int material, uint32_t times, float transparency) {
        for (int k = 0; k < n_; ++k) {
            if (material_[k] == material) {
                count_[k] += times;
                return;
            }
        }
        if (n_ == kMax) {
            for (uint32_t c = 0; c < times; ++c) overflow_ *= transparency;
            return;
        }
        material_[n_] = material;
        count_[n_] = times;
        transparency_[n_] = transparency;
        ++n_;
    }
    float product() {
        // insertion sort by material (n ≤ 32)
        for (int i = 1; i < n_; ++i) {
            for (int j = i; j > 0 && material_[j - 1] > material_[j]; --j) {
                std::swap(material_[j - 1], material_[j]);
                std::swap(count_[j - 1], count_[j]);
                std::swap(transparency_[j - 1], transparency_[j]);
            }
        }
        float T = 1.0f;
        for (int k = 0; k < n_; ++k)
            for (uint32_t c = 0; c < count_[k]; ++c) T *= transparency_[k];
        return T * overflow_;
    }

  private:
    static constexpr int kMax = 32;
    int material_[kMax];
    uint32_t count_[kMax];
    float transparency_[kMax];
    int n_ = 0;
    float overflow_ = 1.0f;  // beyond kMax materials: multiplied as found
};

/// Records n > 0 crossings of a surface of `material`; false if it is opaque (it blocks).
bool add_crossings(const Materials& materials, int material, uint32_t n, Crossings& crossings) {
    const float transparency = materials[material].transparency;
    if (transparency <= 0) return false;
    crossings.add(material, n, transparency);
    return true;
}

/// Every crossing of shape i (not a mesh) with r in (t_min, t_max); false on an opaque one.
/// Inlined: it is the inner loop of every shadow ray.
[[gnu::always_inline]] inline bool cross_shape(const BuiltScene& scene, const Materials& materials,
                                               uint32_t i, const Ray& r, float t_min, float t_max,
                                               Crossings& crossings, IntersectCounters& counters) {
    const Shape& s = scene.shapes[i];
    const bool opaque = materials[s.material].transparency <= 0;
    const uint32_t n = count_crossings(s, r, t_min, t_max, opaque, counters.primitive);
    return n == 0 || add_crossings(materials, s.material, n, crossings);
}

/// Triangle `tri` of mesh shape i; false if it blocks (opaque).
bool cross_triangle(const BuiltScene& scene, const Materials& materials, const WatertightRay& w,
                    const Vec3& p0, const Vec3& p1, const Vec3& p2, uint32_t i, uint32_t tri,
                    float t_min, float t_max, Crossings& crossings, IntersectCounters& counters) {
    ++counters.primitive;
    float t, b1, b2;
    if (!intersect_triangle(w, p0, p1, p2, t_min, t_max, t, b1, b2)) return true;
    return add_crossings(materials, scene.shapes[i].mesh->materials[tri], 1, crossings);
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

/// A small scene without meshes (use_direct): every shape in scene order, its spheres from
/// their groups' roots, the other shapes behind their box when they have no world form. The
/// nearest hit needs no tie rule of its own: a later shape must be strictly nearer to replace
/// an earlier one, so ties keep the lowest shape.
bool nearest_direct(const BuiltScene& scene, const Ray& r, float t_min, float t_max, Hit& hit,
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

/// transmittance() of a small scene without meshes (use_direct), shape by shape.
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

/// Runs f(), adding its duration to counters.query_ns when counters.timing is set.
template <class F>
auto timed(IntersectCounters& counters, F&& f) {
    if (!counters.timing) return f();
    const auto start = std::chrono::steady_clock::now();
    const auto result = f();
    counters.query_ns += static_cast<uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(
                                                   std::chrono::steady_clock::now() - start)
                                                   .count());
    return result;
}

}  // namespace

bool nearest_hit(const BuiltScene& scene, const Ray& r, float t_min, float t_max, Hit& hit,
                 IntersectCounters& counters) {
    return timed(counters, [&] {
        if (use_direct(scene)) return nearest_direct(scene, r, t_min, t_max, hit, counters);
        Best best(t_max);
        const bool found = use_bvh(scene) ? nearest_bvh(scene, r, t_min, best, counters)
                                          : nearest_all(scene, r, t_min, best, counters);
        if (found) hit = best.hit;
        return found;
    });
}

float transmittance(const BuiltScene& scene, const Materials& materials, const Ray& r, float t_min,
                    float t_max, IntersectCounters& counters) {
    return timed(counters, [&] {
        if (use_direct(scene))
            return transmittance_direct(scene, materials, r, t_min, t_max, counters);
        return use_bvh(scene) ? transmittance_bvh(scene, materials, r, t_min, t_max, counters)
                              : transmittance_all(scene, materials, r, t_min, t_max, counters);
    });
}

}  // namespace luz
