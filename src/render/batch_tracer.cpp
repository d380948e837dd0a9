// The batch engine (render/batch_tracer.h): 64 samples at a time, camera rays as packets, the
// hits shaded in lanes, the ray trees level by level. Every rule of the recursion is the
// reference's (render/recursion.h, Whitted).
#include "render/batch_tracer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <vector>

#include "shading/shade_lanes.h"

namespace luz {

namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

/// Runs f(), adding its duration to counters.tests.query_ns when `timed` (a timed batch's scene
/// queries, timed a group of rays at a time).
template <class F>
[[gnu::always_inline]] inline void query(bool timed, TraceCounters& counters, F&& f) {
    if (!timed) {
        f();
        return;
    }
    const auto start = std::chrono::steady_clock::now();
    f();
    counters.tests.query_ns +=
        static_cast<uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(
                                  std::chrono::steady_clock::now() - start)
                                  .count());
}

/// Each light's last occluder (ShadowCache), kept per thread and emptied for every batch of
/// samples (BatchTracer::samples()): the tests a batch does depend on its samples alone.
std::vector<ShadowCache>& batch_shadow_caches() {
    thread_local std::vector<ShadowCache> caches;
    return caches;
}

}  // namespace

void BatchTracer::shade_hits(const Ray* rays, const Hit* hits, unsigned which, bool coherent,
                             bool timed, TraceCounters& counters, ShadedHit* out) const {
    const BuiltScene& scene = ref_.scene();
    const Settings& settings = ref_.settings();
    // The points as Whitted::local() builds them (a ShadingPoint each), by component; the other
    // lanes shaded on zeros and not read.
    ShadingLanes p;
    for (int a = 0; a < 3; ++a) p.P[a] = p.N[a] = p.S[a] = p.ka[a] = p.kd[a] = p.ks[a] = lanes(0);
    p.n = lanes(1.0f);
    Lane8f Ng[3] = {lanes(0.0f), lanes(0.0f), lanes(0.0f)};  // geometric normals (spawns)
    for (unsigned left = which; left != 0; left &= left - 1) {
        const int k = __builtin_ctz(left);
        const Shape& shape = scene.shapes[hits[k].shape];
        const Material& m = settings.materials[material_at(shape, hits[k])];
        const SurfacePoint sp = surface_at(shape, rays[k], hits[k]);
        out[k].sp = sp;
        out[k].shadow_rays = 0;  // raycast; raytrace counts them below
        const SurfaceConstants c = surface_constants(m, sp.P, sp.Ng);
        const Vec3 S = -rays[k].direction;
        for (int a = 0; a < 3; ++a) {
            p.P[a][k] = sp.P[a];
            p.N[a][k] = sp.N[a];
            Ng[a][k] = sp.Ng[a];
            p.S[a][k] = S[a];
            p.ka[a][k] = c.ka[a];
            p.kd[a][k] = c.kd[a];
            p.ks[a][k] = m.ks[a];
        }
        p.n[k] = m.n;
        p.schlick[k] = m.reflectance == Reflectance::schlick ? -1 : 0;
    }
    Lane8f I[3];
    if (!ref_.full()) {
        shade_lanes(p, ref_.lighting(), which, I);
    } else {
        uint64_t shadow_rays[kMaxPacket] = {};
        // vis_j of the lit lanes: their shadow rays P → light j side by side, spawned as
        // Whitted::local() spawns them (spawn_ray(), direction L_j, length d_j).
        ShadowCache* const caches = batch_shadow_caches().data();
        const auto visibility = [&](size_t j, const Lane8f* L, const Lane8f& d, unsigned lit) {
            const Lane8f L_dot_Ng = L[0] * Ng[0] + L[1] * Ng[1] + L[2] * Ng[2];
            const Lane8f offset = lane_select(lane_gt(L_dot_Ng, lanes(0.0f)), lanes(kRayEpsilon),
                                              lanes(-kRayEpsilon));
            SegmentLanes seg;
            store_lanes(seg.ox, p.P[0] + Ng[0] * offset);
            store_lanes(seg.oy, p.P[1] + Ng[1] * offset);
            store_lanes(seg.oz, p.P[2] + Ng[2] * offset);
            store_lanes(seg.dx, L[0]);
            store_lanes(seg.dy, L[1]);
            store_lanes(seg.dz, L[2]);
            store_lanes(seg.t_max, d);
            for (unsigned left = lit; left != 0; left &= left - 1)
                ++shadow_rays[__builtin_ctz(left)];
            alignas(32) float T[kMaxPacket] = {};
            query(timed, counters, [&] {
                transmittances(scene, settings.materials, seg, lit, T, counters.tests, &caches[j],
                               coherent);
            });
            return load_lanes(T);
        };
        shade_lanes(p, ref_.lighting(), which, I, visibility);
        for (int k = 0; k < kMaxPacket; ++k) out[k].shadow_rays = shadow_rays[k];
    }
    for (unsigned left = which; left != 0; left &= left - 1) {
        const int k = __builtin_ctz(left);
        out[k].local = Rgb{I[0][k], I[1][k], I[2][k]};
    }
}

namespace {

/// A ray of a batch's ray trees, traced level by level (BatchTracer::trace_trees()).
struct TreeRay {
    static constexpr int kNone = -1;     ///< no such child (no reflection, no transparency)
    static constexpr int kSkipped = -2;  ///< a child weighing less than min_weight: not traced
    Ray ray;
    float weight = 1.0f;  ///< the product of the coefficients that scale it (Whitted::trace())
    int depth = 0;
    bool refracted = false;  ///< spawned by refraction (else by reflection, or a camera ray)
    int sample = 0;          ///< whose tree: the sample's index in the batch
    int reflection = kNone, refraction = kNone;  ///< the children's indices
    float kr = 0, kt = 0;  ///< the coefficients that scale them (m.reflection, m.transparency)
    bool traced = false;   ///< c and distance known (a camera hit, or traced depth-first)
    float distance = kInfinity;
    Rgb c{0.0f};  ///< the local colour, then all of the colour Whitted::trace() returns
};

/// Whether rays r[0 … q) go one way, each within 60° of the first: the secondary rays of
/// neighbouring hits on one surface, such as those a glass sphere refracts, which go down the
/// BVH faster as a packet; those a small sphere's curve spreads apart, one by one.
bool one_way(const Ray* r, int q) {
    for (int j = 1; j < q; ++j)
        if (dot(r[j].direction, r[0].direction) < 0.5f) return false;
    return true;
}

/// The arrays a batch of samples() and its trees fill, kept per thread: not zeroed for every
/// batch and level.
struct BatchArrays {
    static constexpr int kBatch = 64;  ///< samples whose ray trees are traced together
    Ray camera_rays[kBatch];
    Hit hits[kBatch];
    ShadedHit shaded[kBatch];
    Rgb traced[kBatch];
    // a level's group of rays in trace_trees()
    Ray group_rays[kMaxPacket];
    Hit group_hits[kMaxPacket];
    ShadedHit group_shaded[kMaxPacket];
    std::vector<TreeRay> nodes;   ///< the trees (trace_trees())
    std::vector<uint32_t> level;  ///< a level's rays to trace, in the order they are traced
};

BatchArrays& batch_arrays() {
    thread_local BatchArrays arrays;
    return arrays;
}

}  // namespace

void BatchTracer::trace_trees(const Ray* rays, const Hit* hits, const ShadedHit* shaded,
                              uint64_t packed, bool timed, TraceCounters& counters, Rgb* out,
                              uint64_t* tree_rays) const {
    const BuiltScene& scene = ref_.scene();
    const Settings& settings = ref_.settings();
    const TreeRules& rules = ref_.rules();
    BatchArrays& arrays = batch_arrays();
    std::vector<TreeRay>& nodes = arrays.nodes;
    nodes.clear();
    nodes.reserve(3 * kMaxTreeRays);  // the most a batch appends (kMaxTreeRays)
    const auto material = [&](const Hit& hit) -> const Material& {
        return settings.materials[material_at(scene.shapes[hit.shape], hit)];
    };
    // The secondary rays of node i, hit at sp by a ray in direction D, as Whitted::trace()
    // spawns and counts them: queued for the next level, or (beyond kMaxTreeRays) traced at
    // once by the reference.
    const auto spawn = [&](size_t i, const Vec3& D, const SurfacePoint& sp, const Material& m) {
        // (the parent's fields one by one, the child built in place: no copies of TreeRays)
        const int depth = nodes[i].depth, sample = nodes[i].sample;
        const float weight = nodes[i].weight;
        if (!rules.descends(depth, m)) return;
        const Bounce b = bounce(D, sp, m);
        const auto child = [&](const Vec3& dir, float coefficient, uint64_t& count,
                               bool refracted) {
            const float w = weight * coefficient;
            if (!rules.traced(w)) return TreeRay::kSkipped;
            ++count;
            ++tree_rays[sample];
            const bool keep = nodes.size() < kMaxTreeRays;
            TreeRay& r = nodes.emplace_back();
            r.ray = spawn_ray(sp.P, sp.Ng, dir);
            r.weight = w;
            r.depth = depth + 1;
            r.refracted = refracted;
            r.sample = sample;
            if (!keep) {  // too many to keep for the next level: depth-first
                const uint64_t before = work_of(counters);
                NoObserver none;
                r.c = ref_.trace(r.ray, r.depth, w, counters, r.distance, none);
                r.traced = true;
                tree_rays[sample] += work_of(counters) - before;
            }
            return static_cast<int>(nodes.size() - 1);
        };
        if (m.reflection > 0) {
            nodes[i].reflection = child(b.reflected, m.reflection, counters.reflection, false);
            nodes[i].kr = m.reflection;
        }
        if (m.transparency > 0) {
            nodes[i].refraction = child(b.refracted, m.transparency, counters.refraction, true);
            nodes[i].kt = m.transparency;
        }
    };
    // Level 0: the camera hits, shaded already, then their secondary rays.
    for (uint64_t left = packed; left != 0; left &= left - 1) {
        TreeRay& r = nodes.emplace_back();
        r.sample = __builtin_ctzll(left);
        r.traced = true;
        r.c = shaded[r.sample].local;
    }
    const size_t roots = nodes.size();
    for (size_t i = 0; i < roots; ++i) {
        const int k = nodes[i].sample;
        spawn(i, rays[k].direction, shaded[k].sp, material(hits[k]));
    }
    // Level by level: the rays of one depth eight at a time, found and shaded side by side,
    // those whose last bounce reflected first, then those refracted (neighbours alike: a glass
    // sphere refracts neighbouring rays into neighbouring rays, a packet goes down together).
    std::vector<uint32_t>& level = arrays.level;
    for (size_t begin = roots, end; begin < nodes.size(); begin = end) {
        end = nodes.size();
        level.clear();
        for (const bool refracted : {false, true})
            for (size_t i = begin; i < end; ++i)
                if (!nodes[i].traced && nodes[i].refracted == refracted)
                    level.push_back(static_cast<uint32_t>(i));
        for (size_t i = 0; i < level.size();) {
            size_t group[kMaxPacket];
            Ray* const r = arrays.group_rays;
            int q = 0;
            for (; i < level.size() && q < kMaxPacket; ++i) {
                group[q] = level[i];
                r[q++] = nodes[level[i]].ray;
            }
            if (q == 0) break;
            if (ref_.cancelled()) {  // as Whitted::trace()
                for (int j = 0; j < q; ++j) nodes[group[j]].c = Rgb{0.0f};
                continue;
            }
            Hit* const h = arrays.group_hits;
            bool found[kMaxPacket] = {};
            const bool coherent = one_way(r, q);
            query(timed, counters, [&] {
                if (coherent)
                    nearest_hits(scene, r, q, 0.0f, kInfinity, h, found, counters.tests);
                else
                    nearest_hits_scattered(scene, r, q, 0.0f, kInfinity, h, found, counters.tests);
            });
            unsigned which = 0;  // the rays that hit an object, shaded below
            for (int j = 0; j < q; ++j) {
                TreeRay& node = nodes[group[j]];
                if (found[j]) {
                    which |= 1u << j;
                    node.distance = h[j].t;
                } else {
                    node.c = settings.image.background;  // distance: infinity
                }
            }
            if (ref_.sees_lights()) {  // a light sphere before what a ray met: the light's colour
                for (int j = 0; j < q; ++j) {
                    TreeRay& node = nodes[group[j]];
                    const int light = ref_.nearest_light(r[j], node.distance, counters);
                    if (light < 0) continue;
                    node.c = clamp01(settings.lights[light].intensity);
                    which &= ~(1u << j);
                }
            }
            if (which == 0) continue;
            ShadedHit* const s = arrays.group_shaded;
            shade_hits(r, h, which, coherent, timed, counters, s);
            for (unsigned left = which; left != 0; left &= left - 1) {
                const int j = __builtin_ctz(left);
                TreeRay& node = nodes[group[j]];
                node.c = s[j].local;
                counters.shadow += s[j].shadow_rays;
                tree_rays[node.sample] += s[j].shadow_rays;
                spawn(group[j], r[j].direction, s[j].sp, material(h[j]));
            }
        }
    }
    // The colours, children before parents (they come later), each added as Whitted::trace()
    // adds it: local + A·(reflected)·kr + A·(refracted)·kt.
    const auto returned = [&](int child) {
        if (child == TreeRay::kSkipped) return Rgb{0.0f};
        const TreeRay& r = nodes[static_cast<size_t>(child)];
        return rules.through(r.c, r.distance);
    };
    for (size_t i = nodes.size(); i-- > 0;) {
        TreeRay& r = nodes[i];
        if (r.reflection != TreeRay::kNone) r.c += returned(r.reflection) * r.kr;
        if (r.refraction != TreeRay::kNone) r.c += returned(r.refraction) * r.kt;
    }
    for (size_t i = 0; i < roots; ++i) out[nodes[i].sample] = nodes[i].c;
}

void BatchTracer::samples(const float* px, const float* py, int n, TraceCounters& counters,
                          Rgb* out, uint64_t* rays) const {
    constexpr int kBatch = BatchArrays::kBatch;
    const Settings& settings = ref_.settings();
    BatchArrays& arrays = batch_arrays();
    Ray* const camera_rays = arrays.camera_rays;
    Hit* const hits = arrays.hits;
    ShadedHit* const shaded = arrays.shaded;
    Rgb* const traced = arrays.traced;
    std::vector<ShadowCache>& shadow_caches = batch_shadow_caches();
    for (int first = 0; first < n; first += kBatch) {
        const int m = std::min(kBatch, n - first);
        shadow_caches.assign(settings.lights.size(), ShadowCache{});
        // Timed: a batch holding a sample counted 0 modulo kTimedSampleEvery (a work item's
        // first batch among them), whole and in its queries.
        const uint64_t i0 = counters.primary, i1 = i0 + static_cast<uint64_t>(m) - 1;
        const bool timed =
            i0 % kTimedSampleEvery == 0 || i0 / kTimedSampleEvery != i1 / kTimedSampleEvery;
        const auto start =
            timed ? std::chrono::steady_clock::now() : std::chrono::steady_clock::time_point{};
        uint64_t packed = 0;  // bit k: sample k's camera ray hit an object, shaded in a packet
        for (int p = 0; p < m; p += kMaxPacket) {
            const int q = std::min(kMaxPacket, m - p);
            for (int k = p; k < p + q; ++k)
                camera_rays[k] = ref_.camera().ray(px[first + k], py[first + k]);
            bool found[kMaxPacket] = {};
            if (!ref_.cancelled()) {
                query(timed, counters, [&] {
                    nearest_hits(ref_.scene(), camera_rays + p, q, 0.0f, kInfinity, hits + p, found,
                                 counters.tests);
                });
            }
            // What each camera ray met: an object (shaded below), a light sphere or nothing.
            unsigned which = 0;
            for (int k = 0; k < q; ++k) {
                if (found[k])
                    which |= 1u << k;
                else
                    traced[p + k] = ref_.cancelled() ? Rgb{0.0f} : settings.image.background;
            }
            if (ref_.sees_lights()) {  // a light sphere before what a ray met: the light's colour
                for (int k = 0; k < q; ++k) {
                    float t = found[k] ? hits[p + k].t : kInfinity;
                    const int light = ref_.nearest_light(camera_rays[p + k], t, counters);
                    if (light < 0) continue;
                    traced[p + k] = clamp01(settings.lights[light].intensity);
                    which &= ~(1u << k);
                }
            }
            // The hits shaded side by side, their shadow rays too.
            if (which != 0 && !ref_.cancelled()) {
                shade_hits(camera_rays + p, hits + p, which, true, timed, counters, shaded + p);
                packed |= static_cast<uint64_t>(which) << p;
            }
        }
        // Their secondary rays, the trees of the batch side by side.
        uint64_t tree_rays[kBatch] = {};
        if (ref_.rules().max_depth == 0) {  // raycast, or raytrace without secondary rays
            for (uint64_t left = packed; left != 0; left &= left - 1) {
                const int k = __builtin_ctzll(left);
                traced[k] = shaded[k].local;
            }
        } else if (packed != 0) {
            trace_trees(camera_rays, hits, shaded, packed, timed, counters, traced, tree_rays);
        }
        uint64_t shadow = 0;  // (summed apart: rays[k] might alias the counters)
        for (int k = 0; k < m; ++k) {
            uint64_t sample_rays = 1 + tree_rays[k];
            if ((packed >> k) & 1u) {
                shadow += shaded[k].shadow_rays;
                sample_rays += shaded[k].shadow_rays;
            }
            out[first + k] = traced[k];
            if (rays) rays[first + k] = sample_rays;
        }
        counters.primary += static_cast<uint64_t>(m);
        counters.shadow += shadow;
        if (timed) {
            counters.timed_ns +=
                static_cast<uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(
                                          std::chrono::steady_clock::now() - start)
                                          .count());
        }
    }
}

}  // namespace luz
