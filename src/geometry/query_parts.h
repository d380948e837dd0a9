// What the scene-query strategies share (scene_query.h): the nearest-hit tie rule (Best), the
// transparent crossings of a shadow ray (Crossings), one shape or triangle offered to either,
// and the strategies' entry points (query_bvh.cpp, query_all.cpp, query_leaf_packet.cpp).
#pragma once

#include <cstdint>
#include <utility>

#include "geometry/ray_triangle.h"
#include "geometry/scene_query.h"
#include "geometry/shapes.h"
#include "geometry/sphere_group.h"
#include "math/lane_count.h"
#include "math/next_float.h"

namespace luz::query {

inline Vec3 inverse_direction(const Vec3& d) { return {1.0f / d.x, 1.0f / d.y, 1.0f / d.z}; }

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
inline void offer_shape(const BuiltScene& scene, uint32_t i, const Ray& r, float t_min, Best& best,
                        IntersectCounters& counters) {
    ++counters.primitive;
    Hit h;
    if (intersect(scene.shapes[i], r, t_min, best.limit(), h) && best.better(h.t, i, 0)) {
        best.take(h.t, i, 0, h.u, h.v, h.part);
    }
}

/// The shapes outside the BVH (BuiltScene::unbounded) against r: a plane in world form by its
/// root alone (as intersect() finds it), any other by intersect().
[[gnu::always_inline]] inline void offer_unbounded(const BuiltScene& scene, const Ray& r,
                                                   float t_min, Best& best,
                                                   IntersectCounters& counters) {
    for (const uint32_t i : scene.unbounded) {
        const Shape& s = scene.shapes[i];
        if (!(s.world_form && s.type == ShapeType::plane)) {
            offer_shape(scene, i, r, t_min, best, counters);
            continue;
        }
        ++counters.primitive;
        const float t = shapes::plane::world_root(s, r);
        if (t > t_min && t < best.limit() && best.better(t, i, 0))
            best.take(t, i, 0, 0.0f, 0.0f, part_side);
    }
}

/// Triangle `tri` of shape i, vertices p0, p1, p2, against r.
inline void offer_triangle(const WatertightRay& w, const Vec3& p0, const Vec3& p1, const Vec3& p2,
                           uint32_t i, uint32_t tri, float t_min, Best& best,
                           IntersectCounters& counters) {
    ++counters.primitive;
    float t, b1, b2;
    if (intersect_triangle(w, p0, p1, p2, t_min, best.limit(), t, b1, b2) &&
        best.better(t, i, tri)) {
        best.take(t, i, tri, b1, b2, static_cast<int>(tri));
    }
}

/// The triangles among lanes `lanes` of BVH block b against r by the watertight test, four at
/// a time (intersect_triangles4(); counted in counters): the lanes that hit in (t_min, t_max) at
/// t with barycentrics b1, b2; those to test one by one by the double path (`scalar`); and the
/// lanes that hold shapes (`shapes`, for test_shapes()).
struct BlockTest {
    Lane4f t, b1, b2;
    unsigned hit = 0, scalar = 0, shapes = 0;
};
[[gnu::always_inline]] inline BlockTest test_block(const PrimBlock& b, unsigned lanes,
                                                   const WatertightRay& w, float t_min, float t_max,
                                                   IntersectCounters& counters) {
    BlockTest r;
    const unsigned triangles = b.triangle_lanes() & lanes;
    r.shapes = lanes & ~triangles;
    if (triangles != 0) {
        r.hit = intersect_triangles4(w, b, t_min, t_max, r.t, r.b1, r.b2, r.scalar) & triangles;
        r.scalar &= triangles;
        counters.primitive += static_cast<uint64_t>(lane_count(triangles & ~r.scalar));
    }
    return r;
}

/// The shape lanes `shapes` of block b against r, up to the decision: its world-form spheres
/// and open cylinders four at a time (sphere_lanes_roots(), cylinder_lanes_roots(), ahead only
/// when t_min ≥ 0: the lanes met at roots `spheres.t0`, `spheres.t1`, `spheres.hit`, and the
/// same of `cylinders`, counted), its other shapes around an axis ruled out four at a time where
/// axis_lanes_missed() can (one bounds test), and the lanes left to test one shape at a time
/// (`one_by_one`: other shapes, the axis lanes not ruled out, the spheres and cylinders float
/// cannot be trusted with; counted by their tests).
struct ShapeTest {
    explicit ShapeTest(unsigned shapes) : one_by_one(shapes) {}
    SphereGroupRoots spheres;
    CylinderGroupRoots cylinders;
    unsigned one_by_one;
};
/// test_shapes()'s first part, into r: the shapes around an axis and the open cylinders among
/// `shapes` (a block of spheres alone, the sphereflake's, has none to look for).
[[gnu::always_inline]] inline void test_axial_shapes(const PrimBlock& b, unsigned shapes,
                                                     const Ray& ray, float t_min, ShapeTest& r,
                                                     IntersectCounters& counters) {
    if ((shapes & ~b.sphere_lanes()) == 0) return;
    if (const unsigned axis = b.axis_lanes() & shapes; axis != 0) {
        r.one_by_one &= ~axis_lanes_missed(b, axis, ray);
        ++counters.bounds;
    }
    if (const unsigned cylinders = b.cylinder_lanes() & shapes; cylinders != 0) {
        r.cylinders = cylinder_lanes_roots(b.cylinders(cylinders), ray, t_min >= 0);
        r.one_by_one &= ~cylinders | r.cylinders.slow;
        counters.primitive += static_cast<uint64_t>(lane_count(cylinders & ~r.cylinders.slow));
    }
}
/// test_shapes()'s second part, into r: the spheres among `shapes`.
[[gnu::always_inline]] inline void test_sphere_shapes(const PrimBlock& b, unsigned shapes,
                                                      const Ray& ray, float t_min, ShapeTest& r,
                                                      IntersectCounters& counters) {
    const unsigned spheres = b.sphere_lanes() & shapes;
    if (spheres == 0) return;
    r.spheres = sphere_lanes_roots(b.spheres(spheres), ray, t_min >= 0);
    r.one_by_one &= ~spheres | r.spheres.slow;
    counters.primitive += static_cast<uint64_t>(lane_count(spheres & ~r.spheres.slow));
}
[[gnu::always_inline]] inline ShapeTest test_shapes(const PrimBlock& b, unsigned shapes,
                                                    const Ray& ray, float t_min,
                                                    IntersectCounters& counters) {
    ShapeTest r(shapes);
    test_axial_shapes(b, shapes, ray, t_min, r, counters);
    test_sphere_shapes(b, shapes, ray, t_min, r, counters);
    return r;
}

/// visit(block, lanes) for each block of the leaf of slots first … first + count − 1, with the
/// lanes the leaf uses, until it returns false; whether every block was visited.
template <class Visit>
[[gnu::always_inline]] inline bool for_each_block(const BuiltScene& scene, uint32_t first,
                                                  uint32_t count, Visit&& visit) {
    constexpr uint32_t L = PrimBlock::kLanes;
    const PrimBlock* b = &scene.bvh_blocks[first / L];
    for (uint32_t left = count;; left -= L, ++b) {
        if (!visit(*b, left >= L ? (1u << L) - 1 : (1u << left) - 1)) return false;
        if (left <= L) return true;
    }
}

/// Ray r prepared for the watertight test when a block with triangles first needs it: most rays
/// of shapes on a ground polygon (balls, rings, tree) never meet a triangle (mesh triangles have
/// leaves of their own, scene.cpp), and a mesh's rays pay one test of a bit per block.
struct LazyWatertight {
    WatertightRay w;
    bool ready = false;

    const WatertightRay& for_block(const Ray& r, const PrimBlock& b, unsigned lanes) {
        if (!ready && (b.triangle_lanes() & lanes) != 0) {
            w = prepare_watertight(r);
            ready = true;
        }
        return w;
    }
};

/// The shape lanes `shapes` of BVH block b against r, by Best. Out of line: a mesh's blocks
/// hold none, and their loop stays as small as it was.
[[gnu::noinline]] inline void offer_block_shapes(const BuiltScene& scene, const PrimBlock& b,
                                                 unsigned shapes, const Ray& r, float t_min,
                                                 Best& best, IntersectCounters& counters) {
    const ShapeTest test = test_shapes(b, shapes, r, t_min, counters);
    const auto offer_roots = [&](unsigned hit, const float* t0, const float* t1) {
        for (; hit != 0; hit &= hit - 1) {
            const int k = __builtin_ctz(hit);
            float t;  // the root intersect() would choose
            if (nearest_root(t0[k], t1[k], t_min, best.limit(), t) && best.better(t, b.shape[k], 0))
                best.take(t, b.shape[k], 0, 0.0f, 0.0f, part_side);
        }
    };
    offer_roots(test.spheres.hit, test.spheres.t0, test.spheres.t1);
    offer_roots(test.cylinders.hit, test.cylinders.t0, test.cylinders.t1);
    for (unsigned s = test.one_by_one; s != 0; s &= s - 1)
        offer_shape(scene, b.shape[__builtin_ctz(s)], r, t_min, best, counters);
}

/// Lanes `lanes` of BVH block b against r (w: r prepared for the watertight test), by Best.
/// Inlined: it is the inner loop of every mesh.
[[gnu::always_inline]] inline void offer_block(const BuiltScene& scene, const PrimBlock& b,
                                               unsigned lanes, const Ray& r, const WatertightRay& w,
                                               float t_min, Best& best,
                                               IntersectCounters& counters) {
    const BlockTest test = test_block(b, lanes, w, t_min, best.limit(), counters);
    for (unsigned hit = test.hit; hit != 0; hit &= hit - 1) {
        const int k = __builtin_ctz(hit);
        if (best.better(test.t[k], b.shape[k], b.triangle[k]))
            best.take(test.t[k], b.shape[k], b.triangle[k], test.b1[k], test.b2[k],
                      static_cast<int>(b.triangle[k]));
    }
    for (unsigned one = test.scalar; one != 0; one &= one - 1) {
        const int k = __builtin_ctz(one);
        offer_triangle(w, b.corner(0, k), b.corner(1, k), b.corner(2, k), b.shape[k], b.triangle[k],
                       t_min, best, counters);
    }
    if (test.shapes != 0) offer_block_shapes(scene, b, test.shapes, r, t_min, best, counters);
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

    /// Whether shape i, split into pieces in the BVH (Shape::split), is met here for the first
    /// time: its crossings, all of them, are counted at its first piece met and never again.
    /// Past kMaxSplit such shapes it answers true and lost() becomes true.
    bool first_meeting(uint32_t i) {
        for (int k = 0; k < n_split_; ++k)
            if (split_[k] == i) return false;
        if (n_split_ == kMaxSplit) {
            lost_ = true;
            return true;
        }
        split_[n_split_++] = i;
        return true;
    }
    /// More split shapes were met than first_meeting() remembers: a shape may have been counted
    /// twice, and the product is to be found another way (transmittance_all()).
    bool lost() const { return lost_; }

  private:
    static constexpr int kMax = 32;
    static constexpr int kMaxSplit = 32;
    uint32_t split_[kMaxSplit];
    int n_split_ = 0;
    bool lost_ = false;
    int material_[kMax];
    uint32_t count_[kMax];
    float transparency_[kMax];
    int n_ = 0;
    float overflow_ = 1.0f;  // beyond kMax materials: multiplied as found
};

/// Records n > 0 crossings of a surface of `material`; false if it is opaque (it blocks).
inline bool add_crossings(const Materials& materials, int material, uint32_t n,
                          Crossings& crossings) {
    const float transparency = materials[material].transparency;
    if (transparency <= 0) return false;
    crossings.add(material, n, transparency);
    return true;
}

/// Records n crossings of shape i (not a mesh), a split one's only at the first piece met;
/// false if it is opaque and met (n > 0).
inline bool add_shape_crossings(const BuiltScene& scene, const Materials& materials, uint32_t i,
                                uint32_t n, Crossings& crossings) {
    if (n == 0) return true;
    const Shape& s = scene.shapes[i];
    if (materials[s.material].transparency <= 0) return false;
    return (s.split && !crossings.first_meeting(i)) ||  // counted at another piece
           add_crossings(materials, s.material, n, crossings);
}

/// Every crossing of shape i (not a mesh) with r in (t_min, t_max); false on an opaque one.
/// Inlined: it is the inner loop of every shadow ray.
[[gnu::always_inline]] inline bool cross_shape(const BuiltScene& scene, const Materials& materials,
                                               uint32_t i, const Ray& r, float t_min, float t_max,
                                               Crossings& crossings, IntersectCounters& counters) {
    const Shape& s = scene.shapes[i];
    const bool opaque = materials[s.material].transparency <= 0;  // the first crossing will do
    const uint32_t n = count_crossings(s, r, t_min, t_max, opaque, counters.primitive);
    return add_shape_crossings(scene, materials, i, n, crossings);
}

/// Triangle `tri` of mesh shape i; false if it blocks (opaque).
inline bool cross_triangle(const BuiltScene& scene, const Materials& materials,
                           const WatertightRay& w, const Vec3& p0, const Vec3& p1, const Vec3& p2,
                           uint32_t i, uint32_t tri, float t_min, float t_max, Crossings& crossings,
                           IntersectCounters& counters) {
    ++counters.primitive;
    float t, b1, b2;
    if (!intersect_triangle(w, p0, p1, p2, t_min, t_max, t, b1, b2)) return true;
    return add_crossings(materials, scene.shapes[i].mesh->materials[tri], 1, crossings);
}

/// The shape lanes `shapes` of BVH block b against segment r; false if one is opaque and met.
/// Out of line, as offer_block_shapes().
[[gnu::noinline]] inline bool cross_block_shapes(const BuiltScene& scene,
                                                 const Materials& materials, const PrimBlock& b,
                                                 unsigned shapes, const Ray& r, float t_min,
                                                 float t_max, Crossings& crossings,
                                                 IntersectCounters& counters) {
    // test_shapes() in its two parts, the cylinders first: an opaque one met spares the
    // spheres' test.
    ShapeTest test(shapes);
    test_axial_shapes(b, shapes, r, t_min, test, counters);
    for (unsigned hit = test.cylinders.hit; hit != 0; hit &= hit - 1) {
        const int k = __builtin_ctz(hit);  // counted so, recorded as cross_shape() records them
        const uint32_t n = roots_within(test.cylinders.t0[k], test.cylinders.t1[k], t_min, t_max);
        if (!add_shape_crossings(scene, materials, b.shape[k], n, crossings)) return false;
    }
    test_sphere_shapes(b, shapes, r, t_min, test, counters);
    for (unsigned hit = test.spheres.hit; hit != 0; hit &= hit - 1) {
        const int k = __builtin_ctz(hit);  // as crossings_at_roots() counts them
        const uint32_t n = roots_within(test.spheres.t0[k], test.spheres.t1[k], t_min, t_max);
        if (n > 0 && !add_crossings(materials, scene.shapes[b.shape[k]].material, n, crossings))
            return false;  // (a sphere is never split)
    }
    for (unsigned s = test.one_by_one; s != 0; s &= s - 1) {
        if (!cross_shape(scene, materials, b.shape[__builtin_ctz(s)], r, t_min, t_max, crossings,
                         counters))
            return false;
    }
    return true;
}

/// Lanes `lanes` of BVH block b against segment r; false if it meets an opaque surface.
[[gnu::always_inline]] inline bool cross_block(const BuiltScene& scene, const Materials& materials,
                                               const PrimBlock& b, unsigned lanes, const Ray& r,
                                               const WatertightRay& w, float t_min, float t_max,
                                               Crossings& crossings, IntersectCounters& counters) {
    const BlockTest test = test_block(b, lanes, w, t_min, t_max, counters);
    for (unsigned hit = test.hit; hit != 0; hit &= hit - 1) {
        const int k = __builtin_ctz(hit);
        const int material = scene.shapes[b.shape[k]].mesh->materials[b.triangle[k]];
        if (!add_crossings(materials, material, 1, crossings)) return false;
    }
    for (unsigned one = test.scalar; one != 0; one &= one - 1) {
        const int k = __builtin_ctz(one);
        if (!cross_triangle(scene, materials, w, b.corner(0, k), b.corner(1, k), b.corner(2, k),
                            b.shape[k], b.triangle[k], t_min, t_max, crossings, counters))
            return false;
    }
    return test.shapes == 0 || cross_block_shapes(scene, materials, b, test.shapes, r, t_min, t_max,
                                                  crossings, counters);
}

// The strategies: each answers nearest_hit() and transmittance() (scene_query.h) alone.

/// The scene's BVH, planes apart (query_bvh.cpp).
bool nearest_hit_bvh(const BuiltScene& scene, const Ray& r, float t_min, float t_max, Hit& hit,
                     IntersectCounters& counters);
/// With `cache`: its lanes tested first, then set to the block that blocks r, emptied if none.
float transmittance_bvh(const BuiltScene& scene, const Materials& materials, const Ray& r,
                        float t_min, float t_max, IntersectCounters& counters,
                        ShadowCache* cache = nullptr);
/// nearest_hit_bvh() of up to eight rays, traversed as one packet (query_packet.cpp).
void nearest_hits_bvh(const BuiltScene& scene, const Ray* rays, int n, float t_min, float t_max,
                      Hit* hits, bool* found, IntersectCounters& counters);

/// transmittance_bvh() of the segments `active` of s over (0, t_max[k]) into T[k], traversed as
/// one packet (query_packet.cpp). `cache`, empty, receives the block that blocked the last
/// segment blocked (none: stays empty), as transmittance_bvh() would leave it.
void transmittances_bvh(const BuiltScene& scene, const Materials& materials, const SegmentLanes& s,
                        unsigned active, float* T, IntersectCounters& counters, ShadowCache& cache);

/// Every shape and mesh triangle in scene order, shapes behind their bounds (query_all.cpp).
bool nearest_hit_all(const BuiltScene& scene, const Ray& r, float t_min, float t_max, Hit& hit,
                     IntersectCounters& counters);
float transmittance_all(const BuiltScene& scene, const Materials& materials, const Ray& r,
                        float t_min, float t_max, IntersectCounters& counters);

/// The leaf of slots first … first + count − 1 against rays `active` (bit k: rays[k], prepared
/// for the watertight test in w[k]), each by its Best: the leaf's world-form spheres four rays
/// at a time, its other lanes one ray at a time (query_leaf_packet.cpp); with `unbounded_too`
/// first the scene's unbounded shapes, planes in world form four rays at a time. The same hits
/// and counts as offer_unbounded() and offer_block() ray by ray.
void nearest_hits_leaf(const BuiltScene& scene, uint32_t first, uint32_t count, const Ray* rays,
                       const WatertightRay* w, unsigned active, float t_min, Best* best,
                       IntersectCounters& counters, bool unbounded_too = false);
/// transmittance_bvh() of the segments `active` of s over (0, t_max[k]) into T[k] for a scene
/// whose BVH is the one leaf of slots first … first + count − 1 (BuiltScene::root_leaf): four
/// segments at a time against each of its world-form spheres and each world-form plane
/// (query_leaf_packet.cpp).
void transmittances_leaf(const BuiltScene& scene, const Materials& materials, uint32_t first,
                         uint32_t count, const SegmentLanes& s, unsigned active, float* T,
                         IntersectCounters& counters);

}  // namespace luz::query
