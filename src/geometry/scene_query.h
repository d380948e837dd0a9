// Ray queries on a whole scene: the nearest hit (camera, reflected and refracted rays) and the
// transmittance of a segment (shadow rays), each for one ray or a batch. One interface, two
// strategies giving the same bits (one tie rule, crossings multiplied in material order):
// - query_bvh.cpp: render.accel = bvh — the scene's 8-wide BVH, planes tested apart; a batch
//   goes down it as a packet (query_packet.cpp), its leaves' spheres met by four rays at a
//   time (query_leaf_packet.cpp); a BVH that is one leaf (a few shapes) is tested without
//   the node loop;
// - query_all.cpp: render.accel = none — every shape (behind its bounds) and every triangle.
// The queries see the scene's objects only: light spheres (the lights' `radius`) are not in
// it, so they never block shadow rays; the ray tracer tests them for camera and secondary rays
// itself (render/ray_tracer.cpp).
//
// Shooting rays at one mesh directly (e.g. a benchmark):
//     std::vector<std::string> warnings;
//     SceneDesc d;
//     d.render.pipeline = Pipeline::raytrace;  // build_scene() builds the BVH for ray pipelines
//     d.materials.resize(1);
//     ObjectDesc o;
//     o.type = ShapeType::mesh;
//     o.mesh = std::make_shared<const MeshData>(load_obj("big.obj", false, warnings));
//     d.objects = {o};
//     const BuiltScene scene = build_scene(d);      // scene.bvh_build_seconds, scene.bvh_bytes()
//     IntersectCounters counters;
//     Hit hit;
//     if (nearest_hit(scene, ray, 0.0f, inf, hit, counters)) { /* hit.t, hit.part = triangle */ }
// or use Bvh (bvh.h) alone over any primitives' boxes.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "geometry/hit.h"
#include "geometry/scene.h"
#include "geometry/shapes.h"

namespace luz {

/// Intersection tests counted by the queries (per thread; summed at the end), and the time
/// spent in the queries while `timing` is set (the ray tracer sets it for a sample of rays).
/// The materials a render uses, indexed by Shape::material (Settings::materials): their
/// `transparency` decides what shadow rays pass.
using Materials = std::vector<Material>;

struct IntersectCounters {
    uint64_t primitive = 0;        ///< ray–shape and ray–triangle tests
    uint64_t bounds = 0;           ///< ray–box tests (object bounds, BVH nodes)
    uint64_t nearest_packets = 0;  ///< nearest_hits() calls that took their rays side by side
    uint64_t shadow_packets = 0;   ///< transmittances() calls whose segments went down as one
    bool timing = false;           ///< measure the time spent in nearest_hit and transmittance
    uint64_t query_ns = 0;         ///< nanoseconds spent in them while timing
};

/// Whether ray r meets box b in (t_min, t_max) (slab test; inv_dir = 1/direction).
inline bool hit_bounds(const Bounds3& b, const Ray& r, const Vec3& inv_dir, float t_min,
                       float t_max) {
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

/// The nearest hit of r among the scene's shapes in (t_min, t_max); hit.shape is its index
/// (hit.part the triangle for a mesh). Ties in t go to the lowest shape, then triangle, so
/// that every strategy gives the very same hit.
bool nearest_hit(const BuiltScene& scene, const Ray& r, float t_min, float t_max, Hit& hit,
                 IntersectCounters& counters);

/// The most rays nearest_hits() takes at once.
inline constexpr int kMaxPacket = 8;

/// nearest_hit() of rays[0 … n) (1 ≤ n ≤ kMaxPacket), all over (t_min, t_max): found[k] and
/// hits[k] (set when found) are bit for bit what nearest_hit() gives rays[k]. With the scene's
/// BVH the rays go down it together, as a packet (query_packet.cpp), and four rays meet each
/// sphere of a leaf at once (query_leaf_packet.cpp): for coherent rays, such as neighbouring
/// camera rays, faster than one by one. Otherwise one by one.
void nearest_hits(const BuiltScene& scene, const Ray* rays, int n, float t_min, float t_max,
                  Hit* hits, bool* found, IntersectCounters& counters);

/// nearest_hits() for rays that need not be coherent (the secondary rays of neighbouring
/// pixels): side by side only when the BVH is one leaf (BuiltScene::root_leaf), where that
/// never costs more than one by one; down a deeper BVH one by one (a packet of diverging rays
/// visits the nodes of all of them). The same bits as nearest_hit() either way.
void nearest_hits_scattered(const BuiltScene& scene, const Ray* rays, int n, float t_min,
                            float t_max, Hit* hits, bool* found, IntersectCounters& counters);

/// The product of `transparency` over every surface r crosses in (t_min, t_max): 1 if none,
/// 0 as soon as an opaque one is met (docs/SCENES.md#models: vis_j; a closed glass shape counts
/// twice). The crossings are counted per material and multiplied in material order, so the result
/// does not depend on the order they are found in (up to 32 transparent materials per segment).
/// Only the scene's shapes count: light spheres never block.
float transmittance(const BuiltScene& scene, const Materials& materials, const Ray& r, float t_min,
                    float t_max, IntersectCounters& counters);

/// Up to kMaxPacket segments side by side, by component: segment k starts at (ox, oy, oz)[k],
/// goes along (dx, dy, dz)[k] and ends at t_max[k] (the shadow rays of a packet's points
/// towards one light).
struct SegmentLanes {
    float ox[kMaxPacket], oy[kMaxPacket], oz[kMaxPacket];
    float dx[kMaxPacket], dy[kMaxPacket], dz[kMaxPacket];
    float t_max[kMaxPacket];
    Ray ray(int k) const { return {{ox[k], oy[k], oz[k]}, {dx[k], dy[k], dz[k]}}; }
};

/// The last occluder of one light's shadow rays (the "shadow cache"): the block of the scene's
/// BVH (BuiltScene::bvh_blocks) and its lanes that blocked the last segment traced with it. A
/// segment tests those lanes first, and is blocked without a traversal when one of them meets it
/// opaquely (neighbouring points' shadow rays towards a light are mostly blocked by the same
/// surface). A segment that nothing blocks empties it: the next one goes straight down the BVH
/// (lit points come in runs too). Only the tests done change, never a result: a surface that
/// blocks blocks whatever the order. `lanes` 0: empty.
struct ShadowCache {
    uint32_t block = 0;
    unsigned lanes = 0;
};

/// transmittance(scene, materials, s.ray(k), 0, s.t_max[k]) into T[k] for each segment k of
/// `active` (bit k), bit for bit. When the BVH is one leaf (BuiltScene::root_leaf) four
/// segments meet each of its spheres and each plane at once (query_leaf_packet.cpp); otherwise
/// one by one down the BVH, each first against the occluder of the one before (`cache`, when
/// given, carries it from call to call: the segments of one light) — or, for `coherent`
/// segments (from neighbouring points: the shadow rays of a packet of camera hits) while the
/// cache is empty (lit points come in runs), all of them down the BVH as one packet
/// (query_packet.cpp), a node's tests side by side.
void transmittances(const BuiltScene& scene, const Materials& materials, const SegmentLanes& s,
                    unsigned active, float* T, IntersectCounters& counters,
                    ShadowCache* cache = nullptr, bool coherent = false);

}  // namespace luz
