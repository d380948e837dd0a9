// trace(ray, depth) exactly as docs/SCENES.md#ray-tracing: the lecture's algorithm, the reference
// of every engine.
#include "render/whitted.h"

#include <chrono>
#include <limits>

#include "geometry/ray_sphere.h"
#include "render/term_recorder.h"

namespace luz {

namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

uint64_t nanoseconds_since(std::chrono::steady_clock::time_point start) {
    return static_cast<uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(
                                     std::chrono::steady_clock::now() - start)
                                     .count());
}

}  // namespace

Whitted::Whitted(const BuiltScene& scene, const Settings& settings, bool full,
                 const std::atomic<bool>* cancel)
    : scene_(scene),
      settings_(settings),
      camera_(Camera::from(settings.camera, settings.image.width, settings.image.height)),
      lighting_{settings.render.model, settings.ambient, settings.attenuation_k, settings.lights,
                settings.attenuation},
      rules_(settings, full),
      cancel_(cancel),
      full_(full) {
    for (size_t j = 0; j < settings.lights.size(); ++j)
        if (settings.lights[j].radius > 0) visible_lights_.push_back(static_cast<int>(j));
}

/// coefficient · A · trace(ray, depth + 1), unless the ray weighs less than min_weight.
template <class Observer>
[[gnu::always_inline]] inline Rgb Whitted::secondary(RayKind kind, const Ray& ray,
                                                     float coefficient, int depth, float weight,
                                                     TraceCounters& counters,
                                                     Observer& seen) const {
    const float w = weight * coefficient;
    if (!rules_.traced(w)) return Rgb{0.0f};
    ++(kind == RayKind::reflection ? counters.reflection : counters.refraction);
    float d;
    const Rgb returned = trace(ray, depth + 1, w, counters, d, seen);
    const Rgb contribution = rules_.through(returned, d) * coefficient;
    seen.secondary(kind, coefficient, returned, rules_.A(d), contribution);
    return contribution;
}

[[gnu::always_inline]] inline Rgb Whitted::local(const SurfacePoint& sp, const Vec3& S,
                                                 const Material& m, TraceCounters& counters,
                                                 ShadeTerms* terms) const {
    const ShadingPoint p{sp.P, sp.N, sp.Ng, S, &m};
    if (!full_) return shade(p, lighting_, AllVisible{}, terms);
    // vis_j: the transmittance of the segment P → light j, spawned off the surface. Only the
    // scene's objects can block it (light spheres are not in the scene the query sees).
    auto visibility = [&](size_t, const Vec3& P, const Vec3& L, float d) {
        ++counters.shadow;
        return transmittance(scene_, settings_.materials, spawn_ray(P, sp.Ng, L), 0.0f, d,
                             counters.tests);
    };
    return shade(p, lighting_, visibility, terms);
}

template <class Observer>
Rgb Whitted::trace(const Ray& ray, int depth, float weight, TraceCounters& counters,
                   float& distance, Observer& seen) const {
    distance = kInfinity;
    if (cancelled()) return Rgb{0.0f};  // so that even an exploding ray tree stops at once
    seen.ray(ray, depth);

    // Nearest hit among objects and visible lights.
    Hit hit;
    const bool object = nearest_hit(scene_, ray, 0.0f, distance, hit, counters.tests);
    if (object) distance = hit.t;
    const int light = nearest_light(ray, distance, counters);
    seen.found(distance,
               light >= 0 ? RayHit::light
               : object   ? RayHit::object
                          : RayHit::background,
               light);

    // No hit: the background colour. A light: its intensity, clamped to [0, 1].
    if (light >= 0) return seen.done(clamp01(settings_.lights[light].intensity));
    if (!object) return seen.done(settings_.image.background);

    // Hit object O at P: the local model, with S = −ray.direction and shadow rays.
    const Shape& O = scene_.shapes[hit.shape];
    const int material = material_at(O, hit);
    const Material& m = settings_.materials[material];
    const SurfacePoint sp = surface_at(O, ray, hit);
    ShadeTerms* terms = seen.terms();
    Rgb c = local(sp, -ray.direction, m, counters, terms);
    seen.shaded(hit, material, sp, terms, c);

    // If the depth allows: the reflected and the refracted ray (on total internal reflection
    // the refracted share follows the reflected ray), each weighted by A and its coefficient.
    if (!rules_.descends(depth, m)) return seen.done(c);
    const Bounce b = bounce(ray.direction, sp, m);
    seen.bounced(b);
    if (m.reflection > 0)
        c += secondary(RayKind::reflection, spawn_ray(sp.P, sp.Ng, b.reflected), m.reflection,
                       depth, weight, counters, seen);
    if (m.transparency > 0)
        c += secondary(RayKind::refraction, spawn_ray(sp.P, sp.Ng, b.refracted), m.transparency,
                       depth, weight, counters, seen);
    return seen.done(c);
}

int Whitted::nearest_light_sphere(const Ray& ray, float& t_max, TraceCounters& counters) const {
    int nearest = -1;
    for (int j : visible_lights_) {
        const Light& light = settings_.lights[j];
        ++counters.tests.primitive;
        float t0, t1, t;
        if (world_sphere_roots(light.position, light.radius, ray, t0, t1) &&
            nearest_root(t0, t1, 0.0f, t_max, t)) {
            t_max = t;
            nearest = j;
        }
    }
    return nearest;
}

Rgb Whitted::sample(float px, float py, TraceCounters& counters) const {
    float distance;
    NoObserver none;
    const Ray ray = camera_.ray(px, py);
    // A work item's first sample and every kTimedSampleEvery-th after it: whole, and in its
    // scene queries (IntersectCounters::timing).
    if (counters.primary++ % kTimedSampleEvery != 0)
        return trace(ray, 0, 1.0f, counters, distance, none);
    const auto start = std::chrono::steady_clock::now();
    counters.tests.timing = true;
    const Rgb c = trace(ray, 0, 1.0f, counters, distance, none);
    counters.tests.timing = false;
    counters.timed_ns += nanoseconds_since(start);
    return c;
}

TermSample Whitted::sample_terms(float px, float py, TraceCounters& counters) const {
    TermSample s;
    TermRecorder terms(s, settings_.lights.size());
    const uint64_t tests_before = counters.tests.primitive;
    float distance;
    const bool timed = counters.primary++ % kTimedSampleEvery == 0;  // as sample()
    const auto start = std::chrono::steady_clock::now();
    counters.tests.timing = timed;
    s.colour = trace(camera_.ray(px, py), 0, 1.0f, counters, distance, terms);
    counters.tests.timing = false;
    if (timed) counters.timed_ns += nanoseconds_since(start);
    s.tests = static_cast<float>(counters.tests.primitive - tests_before);
    return s;
}

template Rgb Whitted::trace(const Ray&, int, float, TraceCounters&, float&, NoObserver&) const;
template Rgb Whitted::trace(const Ray&, int, float, TraceCounters&, float&, RayTreeRecorder&) const;

}  // namespace luz
