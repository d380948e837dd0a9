// trace(ray, depth) exactly as SPEC §1.1.
#include "render/ray_tracer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <span>
#include <vector>

#include "geometry/ray_sphere.h"
#include "shading/shade_lanes.h"

namespace luz {

namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

/// Ray–sphere hit in (0, t_max) for a light sphere (centre c, radius r), nearest first: the
/// scene's one ray–sphere routine (geometry/ray_sphere.h).
bool hit_light_sphere(const Ray& ray, const Vec3& c, float r, float t_max, float& t) {
    float t0, t1;
    return world_sphere_roots(c, r, ray, t0, t1) && nearest_root(t0, t1, 0.0f, t_max, t);
}

/// Nanoseconds from `start` to now (the timed samples).
uint64_t nanoseconds_since(std::chrono::steady_clock::time_point start) {
    return static_cast<uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(
                                     std::chrono::steady_clock::now() - start)
                                     .count());
}

/// Per-thread light terms of a primary hit whose terms are asked for (no allocation per sample).
std::span<LightTerm> light_scratch(size_t lights) {
    thread_local std::vector<LightTerm> scratch;
    scratch.assign(lights, LightTerm{});
    return scratch;
}

}  // namespace

bool refract(const Vec3& D, const Vec3& N, float n1, float n2, Vec3& T) {
    const float eta = n1 / n2;
    const float cos_i = -dot(D, N);
    const float k = 1 - eta * eta * (1 - cos_i * cos_i);  // cos² r
    if (k < 0) return false;                              // total internal reflection
    T = normalize(D * eta + N * (eta * cos_i - std::sqrt(k)));
    return true;
}

Bounce bounce(const Vec3& D, const SurfacePoint& sp, const Material& m) {
    const bool entering = dot(D, sp.Ng) < 0;
    const Vec3 N = dot(D, sp.N) < 0 ? sp.N : -sp.N;  // facing the incoming ray
    Bounce b;
    b.reflected = reflect(D, N);
    if (m.transparency > 0) {
        const float n1 = entering ? 1.0f : m.ior, n2 = entering ? m.ior : 1.0f;
        Vec3 T;
        b.tir = !refract(D, N, n1, n2, T);
        b.refracted = b.tir ? b.reflected : T;
    }
    return b;
}

RayTracer::RayTracer(const BuiltScene& scene, const Settings& settings, bool full,
                     const std::atomic<bool>* cancel)
    : scene_(scene),
      settings_(settings),
      camera_(Camera::from(settings.camera, settings.image.width, settings.image.height)),
      lighting_{settings.render.model, settings.ambient, settings.attenuation_k, settings.lights},
      max_depth_(full ? settings.render.max_depth : 0),
      min_weight_(settings.render.min_weight),
      cancel_(cancel),
      full_(full),
      tree_attenuation_(settings.render.tree_attenuation) {
    for (size_t j = 0; j < settings.lights.size(); ++j)
        if (settings.lights[j].radius > 0) visible_lights_.push_back(static_cast<int>(j));
}

int RayTracer::nearest_light(const Ray& ray, float& t_max, TraceCounters& counters) const {
    int nearest = -1;
    for (int j : visible_lights_) {
        const Light& light = settings_.lights[j];
        ++counters.tests.primitive;
        float t;
        if (hit_light_sphere(ray, light.position, light.radius, t_max, t)) {
            t_max = t;
            nearest = j;
        }
    }
    return nearest;
}

Rgb RayTracer::trace(const Ray& ray, int depth, TraceCounters& counters, float& distance,
                     RayTree* tree) const {
    return tree ? trace_impl<true>(ray, depth, 1.0f, counters, distance, tree)
                : trace_impl<false>(ray, depth, 1.0f, counters, distance, nullptr);
}

template <bool kRecord, bool kTerms>
Rgb RayTracer::trace_impl(const Ray& ray, int depth, float weight, TraceCounters& counters,
                          float& distance, RayTree* tree_in, TermSample* terms_in,
                          const std::pair<bool, Hit>* primary) const {
    // Cancelled: return at once, so that even an exploding ray tree stops within a moment (a
    // relaxed load per ray: no measurable cost).
    if (cancel_ && cancel_->load(std::memory_order_relaxed)) {
        distance = kInfinity;
        return Rgb{0.0f};
    }
    RayTree* const tree = kRecord ? tree_in : nullptr;  // a constant null when not recording
    const Settings& desc = settings_;
    // Ray-tree recording (viewer only): this ray's node, filled as the numbers are computed.
    int self = -1;
    if (tree) {
        self = static_cast<int>(tree->nodes.size());
        RayTreeNode& n = tree->nodes.emplace_back();
        n.depth = depth;
        n.origin = ray.origin;
        n.direction = ray.direction;
    }
    auto record = [&](const Rgb& c) {
        if (tree) tree->nodes[self].color = c;
        return c;
    };
    // The primary ray's terms (SPEC §1.5), filled as the numbers are computed.
    TermSample* const out = kTerms ? terms_in : nullptr;
    // Nearest hit among objects (unless the caller found it) and visible lights.
    float t_max = kInfinity;
    Hit hit;
    if (primary) hit = primary->second;
    const bool hit_object =
        primary ? primary->first : nearest_hit(scene_, ray, 0.0f, t_max, hit, counters.tests);
    if (hit_object) t_max = hit.t;
    const int light = visible_lights_.empty() ? -1 : nearest_light(ray, t_max, counters);
    distance = t_max;
    if (tree) {
        RayTreeNode& n = tree->nodes[self];
        n.t = t_max;
        n.hit = light >= 0 ? RayHit::light : hit_object ? RayHit::object : RayHit::background;
        n.light = light;
    }
    if constexpr (kTerms) out->depth = t_max;  // +inf on a miss
    if (light >= 0) {
        const Rgb emitted = clamp01(desc.lights[light].intensity);
        if constexpr (kTerms) out->emitted = emitted;
        return record(emitted);
    }
    if (!hit_object) {
        if constexpr (kTerms) out->emitted = desc.image.background;
        return record(desc.image.background);
    }

    // The local model at P, with S = −ray.direction and shadow rays (raytrace).
    const Shape& shape = scene_.shapes[hit.shape];
    const Material& m = desc.materials[material_at(shape, hit)];
    const SurfacePoint sp = surface_at(shape, ray, hit);
    const Vec3 D = ray.direction;
    const ShadingPoint p{sp.P, sp.N, sp.Ng, -D, &m};
    ShadeTerms terms;
    ShadeTerms* terms_out = nullptr;
    if constexpr (kTerms) {
        terms.light = light_scratch(desc.lights.size());
        terms_out = &terms;
    }
    if (tree) {
        RayTreeNode& n = tree->nodes[self];
        n.object = static_cast<int>(hit.shape);
        n.material = static_cast<int>(&m - desc.materials.data());
        n.P = sp.P;
        n.N = sp.N;
        n.lights.resize(desc.lights.size());
        terms.light = n.lights;
        terms_out = &terms;
    }
    Rgb c;
    if (full_) {
        auto visibility = [&](size_t, const Vec3& P, const Vec3& L, float d) {
            ++counters.shadow;
            // The segment P → light j moved by the spawn offset (≤ 1e-4): direction L, length d.
            // Only the scene's objects can block it: light spheres never block shadow rays
            // (they are not in the scene the query sees; scene_query.h).
            return transmittance(scene_, desc.materials, spawn_ray(P, sp.Ng, L), 0.0f, d,
                                 counters.tests);
        };
        c = shade(p, lighting_, visibility, terms_out);
    } else {
        c = shade(p, lighting_, AllVisible{}, terms_out);
    }
    if (tree) {
        RayTreeNode& n = tree->nodes[self];
        n.ambient = terms.ambient;
        n.flipped = terms.flipped;
        n.local = c;
    }
    if constexpr (kTerms) {
        out->ambient = terms.ambient;
        for (const LightTerm& t : terms.light) {
            out->diffuse += t.diffuse;
            out->specular += t.specular;
            out->shadow += t.unshadowed * (1.0f - t.visibility);  // (1 − vis_j)·(…with vis_j = 1)
        }
        out->normal = terms.flipped ? -sp.N : sp.N;
    }
    if (depth >= max_depth_ || (m.reflection <= 0 && m.transparency <= 0)) return record(c);

    const Bounce b = bounce(D, sp, m);
    const float K = desc.attenuation_k;
    // A = 1, or 1/(d+K) for the secondary segment's length d (SPEC §1.1: tree_attenuation).
    int child = -1;  // the last secondary ray's node (ray-tree recording; -1: not recorded)
    // A secondary ray scaled by `coefficient`: traced unless its weight is below min_weight.
    auto secondary = [&](const Ray& r, float coefficient, uint64_t& count) {
        child = -1;
        const float w = weight * coefficient;  // SPEC §2: render.min_weight
        if (w < min_weight_) return Rgb{0.0f};
        ++count;
        float d;
        Rgb s;
        if (tree && tree->nodes.size() >= kRayTreeMaxNodes) {  // cut: traced, not recorded
            tree->truncated = true;
            s = trace_impl<false, false>(r, depth + 1, w, counters, d, nullptr);
        } else {
            if (tree) child = static_cast<int>(tree->nodes.size());
            s = trace_impl<kRecord, false>(r, depth + 1, w, counters, d, tree);
        }
        if (tree && child >= 0) {
            tree->nodes[child].returned = s;
            tree->nodes[child].A = !tree_attenuation_ ? 1.0f
                                   : std::isinf(d)    ? 0.0f
                                                      : 1.0f / (d + K);
        }
        if (!tree_attenuation_) return s;
        return std::isinf(d) ? Rgb{0.0f} : s * (1.0f / (d + K));
    };
    // Records a child's kind, weight and contribution (ray-tree recording).
    auto record_child = [&](RayKind kind, float coefficient, const Rgb& contribution) {
        if (child < 0) return;  // not traced (min_weight) or beyond the recording cap
        RayTreeNode& n = tree->nodes[child];
        n.kind = kind;
        n.parent = self;
        n.coefficient = coefficient;
        n.contribution = contribution;
        (kind == RayKind::reflection ? tree->nodes[self].reflection_child
                                     : tree->nodes[self].refraction_child) = child;
    };
    if (m.reflection > 0) {
        const Rgb contribution =
            secondary(spawn_ray(sp.P, sp.Ng, b.reflected), m.reflection, counters.reflection) *
            m.reflection;
        c += contribution;
        if constexpr (kTerms) out->reflected = contribution;
        if (tree) record_child(RayKind::reflection, m.reflection, contribution);
    }
    if (m.transparency > 0) {
        const Rgb contribution =
            secondary(spawn_ray(sp.P, sp.Ng, b.refracted), m.transparency, counters.refraction) *
            m.transparency;
        c += contribution;
        if constexpr (kTerms) out->refracted = contribution;
        if (tree) {
            record_child(RayKind::refraction, m.transparency, contribution);
            tree->nodes[self].total_internal_reflection = b.tir;
        }
    }
    return record(c);
}

Rgb RayTracer::sample(float px, float py, TraceCounters& counters) const {
    float distance;
    // A work item's first sample and every kTimedSampleEvery-th after it: every render that
    // traces a ray times at least one.
    if (counters.primary++ % kTimedSampleEvery != 0) {
        return trace_impl<false>(camera_.ray(px, py), 0, 1.0f, counters, distance, nullptr);
    }
    // A timed sample: the whole of it, and its scene queries (IntersectCounters::timing).
    const auto start = std::chrono::steady_clock::now();
    counters.tests.timing = true;
    const Rgb c = trace_impl<false>(camera_.ray(px, py), 0, 1.0f, counters, distance, nullptr);
    counters.tests.timing = false;
    counters.timed_ns += nanoseconds_since(start);
    return c;
}

void RayTracer::shade_hits(const Ray* rays, const Hit* hits, unsigned which,
                           TraceCounters& counters, ShadedHit* out) const {
    // The points as trace_impl() builds them (a ShadingPoint each), by component; the other
    // lanes shaded on zeros and not read.
    ShadingLanes p;
    for (int a = 0; a < 3; ++a) p.P[a] = p.N[a] = p.S[a] = p.ka[a] = p.kd[a] = p.ks[a] = lanes(0);
    p.n = lanes(1.0f);
    Lane8f Ng[3] = {lanes(0.0f), lanes(0.0f), lanes(0.0f)};  // geometric normals (spawns)
    for (unsigned left = which; left != 0; left &= left - 1) {
        const int k = __builtin_ctz(left);
        const Shape& shape = scene_.shapes[hits[k].shape];
        const Material& m = settings_.materials[material_at(shape, hits[k])];
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
    if (!full_) {
        shade_lanes(p, lighting_, which, I);
    } else {
        uint64_t shadow_rays[kMaxPacket] = {};
        // vis_j of the lit lanes: their shadow rays P → light j side by side, spawned as
        // trace_impl()'s visibility spawns them (spawn_ray(), direction L_j, length d_j).
        const auto visibility = [&](size_t, const Lane8f* L, const Lane8f& d, unsigned lit) {
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
            transmittances(scene_, settings_.materials, seg, lit, T, counters.tests);
            return load_lanes(T);
        };
        shade_lanes(p, lighting_, which, I, visibility);
        for (int k = 0; k < kMaxPacket; ++k) out[k].shadow_rays = shadow_rays[k];
    }
    for (unsigned left = which; left != 0; left &= left - 1) {
        const int k = __builtin_ctz(left);
        out[k].local = Rgb{I[0][k], I[1][k], I[2][k]};
    }
}

namespace {

/// A ray of a batch's ray trees, traced level by level (RayTracer::trace_trees()).
struct TreeRay {
    static constexpr int kNone = -1;     ///< no such child (no reflection, no transparency)
    static constexpr int kSkipped = -2;  ///< a child weighing less than min_weight: not traced
    Ray ray;
    float weight = 1.0f;  ///< the product of the coefficients that scale it (trace_impl())
    int depth = 0;
    int sample = 0;                              ///< whose tree: the sample's index in the batch
    int reflection = kNone, refraction = kNone;  ///< the children's indices
    float kr = 0, kt = 0;  ///< the coefficients that scale them (m.reflection, m.transparency)
    bool traced = false;   ///< c and distance known (a camera hit, or traced depth-first)
    float distance = kInfinity;
    Rgb c{0.0f};  ///< the local colour, then all of the colour trace_impl() returns
};

/// The arrays a batch of samples() and its trees fill, kept per thread: zeroing them for every
/// batch and level (their members' defaults) took 6 % of a Whitted frame.
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
    std::vector<TreeRay> nodes;  ///< the trees (trace_trees())
};

BatchArrays& batch_arrays() {
    thread_local BatchArrays arrays;
    return arrays;
}

}  // namespace

void RayTracer::trace_trees(const Ray* rays, const Hit* hits, const ShadedHit* shaded,
                            uint64_t packed, TraceCounters& counters, Rgb* out,
                            uint64_t* tree_rays) const {
    BatchArrays& arrays = batch_arrays();
    std::vector<TreeRay>& nodes = arrays.nodes;
    nodes.clear();
    nodes.reserve(3 * kMaxTreeRays);  // the most a batch appends (kMaxTreeRays)
    const auto material = [&](const Hit& hit) -> const Material& {
        return settings_.materials[material_at(scene_.shapes[hit.shape], hit)];
    };
    // The secondary rays of node i, hit at sp by a ray in direction D, as trace_impl() spawns
    // and counts them: queued for the next level, or (beyond kMaxTreeRays) traced at once.
    const auto spawn = [&](size_t i, const Vec3& D, const SurfacePoint& sp, const Material& m) {
        // (the parent's fields one by one, the child built in place: no copies of TreeRays)
        const int depth = nodes[i].depth, sample = nodes[i].sample;
        const float weight = nodes[i].weight;
        if (depth >= max_depth_ || (m.reflection <= 0 && m.transparency <= 0)) return;
        const Bounce b = bounce(D, sp, m);
        const auto child = [&](const Vec3& dir, float coefficient, uint64_t& count) {
            const float w = weight * coefficient;
            if (w < min_weight_) return TreeRay::kSkipped;
            ++count;
            ++tree_rays[sample];
            const bool keep = nodes.size() < kMaxTreeRays;
            TreeRay& r = nodes.emplace_back();
            r.ray = spawn_ray(sp.P, sp.Ng, dir);
            r.weight = w;
            r.depth = depth + 1;
            r.sample = sample;
            if (!keep) {  // too many to keep for the next level: depth-first
                const uint64_t before = work_of(counters);
                r.c = trace_impl<false>(r.ray, r.depth, w, counters, r.distance, nullptr);
                r.traced = true;
                tree_rays[sample] += work_of(counters) - before;
            }
            return static_cast<int>(nodes.size() - 1);
        };
        if (m.reflection > 0) {
            nodes[i].reflection = child(b.reflected, m.reflection, counters.reflection);
            nodes[i].kr = m.reflection;
        }
        if (m.transparency > 0) {
            nodes[i].refraction = child(b.refracted, m.transparency, counters.refraction);
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
    // Level by level: the rays of one depth eight at a time, found and shaded side by side.
    for (size_t begin = roots, end; begin < nodes.size(); begin = end) {
        end = nodes.size();
        for (size_t i = begin; i < end;) {
            size_t group[kMaxPacket];
            Ray* const r = arrays.group_rays;
            int q = 0;
            for (; i < end && q < kMaxPacket; ++i) {
                if (nodes[i].traced) continue;
                group[q] = i;
                r[q++] = nodes[i].ray;
            }
            if (q == 0) break;
            if (cancel_ && cancel_->load(std::memory_order_relaxed)) {  // as trace_impl()
                for (int j = 0; j < q; ++j) nodes[group[j]].c = Rgb{0.0f};
                continue;
            }
            Hit* const h = arrays.group_hits;
            bool found[kMaxPacket] = {};
            nearest_hits_scattered(scene_, r, q, 0.0f, kInfinity, h, found, counters.tests);
            unsigned which = 0;
            for (int j = 0; j < q; ++j) {
                if (found[j]) {
                    which |= 1u << j;
                    nodes[group[j]].distance = h[j].t;
                } else {
                    nodes[group[j]].c = settings_.image.background;  // distance: infinity
                }
            }
            if (which == 0) continue;
            ShadedHit* const s = arrays.group_shaded;
            shade_hits(r, h, which, counters, s);
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
    // The colours, children before parents (they come later), each added as trace_impl()
    // adds it: local + (reflected)·kr + (refracted)·kt, A = 1/(d+K) if tree_attenuation.
    const float K = settings_.attenuation_k;
    const auto returned = [&](int child) {
        if (child == TreeRay::kSkipped) return Rgb{0.0f};
        const TreeRay& r = nodes[static_cast<size_t>(child)];
        if (!tree_attenuation_) return r.c;
        return std::isinf(r.distance) ? Rgb{0.0f} : r.c * (1.0f / (r.distance + K));
    };
    for (size_t i = nodes.size(); i-- > 0;) {
        TreeRay& r = nodes[i];
        if (r.reflection != TreeRay::kNone) r.c += returned(r.reflection) * r.kr;
        if (r.refraction != TreeRay::kNone) r.c += returned(r.refraction) * r.kt;
    }
    for (size_t i = 0; i < roots; ++i) out[nodes[i].sample] = nodes[i].c;
}

void RayTracer::samples(const float* px, const float* py, int n, TraceCounters& counters, Rgb* out,
                        uint64_t* rays) const {
    constexpr int kBatch = BatchArrays::kBatch;
    const auto cancelled = [&] { return cancel_ && cancel_->load(std::memory_order_relaxed); };
    BatchArrays& arrays = batch_arrays();
    Ray* const camera_rays = arrays.camera_rays;
    Hit* const hits = arrays.hits;
    ShadedHit* const shaded = arrays.shaded;
    Rgb* const traced = arrays.traced;
    for (int first = 0; first < n; first += kBatch) {
        const int m = std::min(kBatch, n - first);
        bool found[kBatch] = {};
        uint64_t packet_ns[kBatch / kMaxPacket] = {};
        uint64_t packed = 0;  // bit k: sample k's camera hit shaded in a packet
        const uint64_t base = counters.primary;
        for (int p = 0; p < m; p += kMaxPacket) {
            const int q = std::min(kMaxPacket, m - p);
            for (int k = p; k < p + q; ++k)
                camera_rays[k] = camera_.ray(px[first + k], py[first + k]);
            // Timed as sample() times, every kTimedSampleEvery-th sample whole: the packet's
            // query, when the packet holds one, is timed and counted for each timed sample by
            // its share (1/q); the others' rays are not timed (a clock read costs as much as a
            // shadow ray).
            const uint64_t i0 = base + static_cast<uint64_t>(p), i1 = i0 + q - 1;
            const bool timed =
                i0 % kTimedSampleEvery == 0 || i0 / kTimedSampleEvery != i1 / kTimedSampleEvery;
            if (!cancelled()) {
                const auto start = timed ? std::chrono::steady_clock::now()
                                         : std::chrono::steady_clock::time_point{};
                nearest_hits(scene_, camera_rays + p, q, 0.0f, kInfinity, hits + p, found + p,
                             counters.tests);
                if (timed) packet_ns[p / kMaxPacket] = nanoseconds_since(start);
            }
            // The hits shaded side by side (their shadow rays too), those of untimed samples (a
            // timed one is traced whole, as sample() traces it) when no light sphere can come
            // before them.
            if (visible_lights_.empty() && !cancelled()) {
                unsigned which = 0;
                for (int k = 0; k < q; ++k)
                    if (found[p + k] && (i0 + static_cast<uint64_t>(k)) % kTimedSampleEvery != 0)
                        which |= 1u << k;
                if (which != 0) shade_hits(camera_rays + p, hits + p, which, counters, shaded + p);
                packed |= static_cast<uint64_t>(which) << p;
            }
        }
        // Their secondary rays, the trees of the batch side by side.
        uint64_t tree_rays[kBatch] = {};
        if (max_depth_ == 0) {  // raycast, or raytrace without secondary rays: no trees
            for (uint64_t left = packed; left != 0; left &= left - 1) {
                const int k = __builtin_ctzll(left);
                traced[k] = shaded[k].local;
            }
        } else if (packed != 0) {
            trace_trees(camera_rays, hits, shaded, packed, counters, traced, tree_rays);
        }
        for (int k = 0; k < m; ++k) {
            const uint64_t before = work_of(counters);
            const bool timed_sample = counters.primary++ % kTimedSampleEvery == 0;
            const bool in_tree = (packed >> k) & 1u;
            if (in_tree) {
                counters.shadow += shaded[k].shadow_rays;
                out[first + k] = traced[k];
            } else {
                const auto start = timed_sample ? std::chrono::steady_clock::now()
                                                : std::chrono::steady_clock::time_point{};
                counters.tests.timing = timed_sample;
                const std::pair<bool, Hit> primary{found[k], hits[k]};
                float distance;
                out[first + k] = trace_impl<false>(camera_rays[k], 0, 1.0f, counters, distance,
                                                   nullptr, nullptr, &primary);
                counters.tests.timing = false;
                if (timed_sample) {
                    const int p = k / kMaxPacket * kMaxPacket;
                    const uint64_t q = static_cast<uint64_t>(std::min(kMaxPacket, m - p));
                    const uint64_t share = packet_ns[p / kMaxPacket] / q;
                    counters.tests.query_ns += share;
                    counters.timed_ns += nanoseconds_since(start) + share;
                }
            }
            if (rays) rays[first + k] = work_of(counters) - before + tree_rays[k];
        }
    }
}

TermSample RayTracer::sample_terms(float px, float py, TraceCounters& counters) const {
    // Timed like sample(): the same samples are timed whichever is called.
    TermSample s;
    const uint64_t tests_before = counters.tests.primitive;
    float distance;
    const bool timed = counters.primary++ % kTimedSampleEvery == 0;
    const auto start = std::chrono::steady_clock::now();
    counters.tests.timing = timed;
    s.colour =
        trace_impl<false, true>(camera_.ray(px, py), 0, 1.0f, counters, distance, nullptr, &s);
    counters.tests.timing = false;
    if (timed) {
        counters.timed_ns += nanoseconds_since(start);
    }
    s.tests = static_cast<float>(counters.tests.primitive - tests_before);
    return s;
}

}  // namespace luz
