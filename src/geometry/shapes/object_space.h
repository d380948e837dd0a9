// What the shapes share to be hit in their canonical object space: double vectors, the nearest
// accepted root, the quadratic, the crossing count by repeated hits, and surface data from an
// object-space normal.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "geometry/hit.h"
#include "geometry/ray_sphere.h"
#include "geometry/shape.h"
#include "math/ray.h"

namespace luz::shapes {

/// A double-precision point or vector for the solvers (object space).
using D3 = Lane3<double>;
inline D3 to_d3(const Vec3& v) { return {v.x, v.y, v.z}; }
inline D3 along(const D3& o, const D3& d, double t) {
    return {o.x + t * d.x, o.y + t * d.y, o.z + t * d.z};
}

/// Normalised, or `fallback` for a zero (or non-finite) vector.
inline Vec3 unit_or(const Vec3& v, const Vec3& fallback) {
    const float l = length(v);
    return (l > 0 && std::isfinite(l)) ? v / l : fallback;
}

/// The nearest accepted candidate so far. A candidate root t (double) is accepted if, rounded
/// to float, it lies in (t_min, best): the returned t always satisfies t_min < t < t_max.
struct Nearest {
    float t_min;
    float best;  // t_max until something is found
    double t = 0;
    int part = part_side;
    bool found = false;

    bool offer(double candidate, int p) {
        const float tf = static_cast<float>(candidate);  // NaN and ±inf fail below
        if (tf > t_min && tf < best) {
            best = tf;
            t = candidate;
            part = p;
            found = true;
            return true;
        }
        return false;
    }
};

/// Real roots of a·t² + 2·b·t + c = 0 (note the half coefficient b) in the cancellation-free
/// form q = −(b + sign(b)·√disc), roots c/q and q/a; disc = b² − a·c is passed in so callers can
/// compute it in their best-conditioned way. A root that does not exist comes out ±inf or NaN,
/// which Nearest::offer rejects (a = 0: the linear case keeps its root c/q).
inline void quadratic_roots(double a, double b, double c, double disc, double& r0, double& r1) {
    const double q = -(b + std::copysign(std::sqrt(disc), b));
    r0 = c / q;
    r1 = q / a;
}

/// intersect() for a shape hit in object space: `hit_object(ro, nearest)` offers the roots of
/// the object-space ray ro (transform.to_object, direction not normalised, so t is the same in
/// both spaces) and returns whether one was accepted. Out of line, as count_by_repeated_hits():
/// the world-form paths stay inline in the queries' loops, these would only crowd them.
template <class HitObject>
[[gnu::noinline]] bool intersect_in_object_space(const Shape& s, const Ray& r, float t_min,
                                                 float t_max, Hit& hit,
                                                 const HitObject& hit_object) {
    Nearest n{t_min, t_max};
    hit.u = hit.v = 0;
    const Ray ro = s.transform.to_object(r);
    if (!hit_object(ro, n)) return false;
    hit.t = n.best;
    hit.part = n.part;
    return true;
}

/// intersect() from the roots t0 ≤ t1 of a shape in world form (Shape::world_form).
inline bool hit_at_roots(float t0, float t1, float t_min, float t_max, Hit& hit) {
    float t;
    if (!nearest_root(t0, t1, t_min, t_max, t)) return false;
    hit.t = t;
    hit.u = hit.v = 0;
    hit.part = part_side;
    return true;
}

/// count_crossings() for shapes without a closed form: repeats `intersect(t_min, t_max, hit)`
/// past each crossing (up to 64), or stops at the first with `first_only`; `tests` counts the
/// tests made.
template <class Intersect>
[[gnu::noinline]] uint32_t count_by_repeated_hits(float t_min, float t_max, bool first_only,
                                                  uint64_t& tests, const Intersect& intersect) {
    Hit hit;
    float t = t_min;
    uint32_t n = 0;
    for (int k = 0; k < 64; ++k) {
        ++tests;
        if (!intersect(t, t_max, hit)) break;
        ++n;
        if (first_only) break;
        // Step past this crossing (relative step: the same root is not found twice).
        t = hit.t + 1e-4f * std::max(1.0f, hit.t);
    }
    return n;
}

/// count_crossings() from the roots of a shape in world form, if `met` (t1 NaN for a single
/// root): one test.
inline uint32_t crossings_at_roots(bool met, float t0, float t1, float t_min, float t_max,
                                   bool first_only, uint64_t& tests) {
    ++tests;
    if (!met) return 0;
    const uint32_t n = roots_within(t0, t1, t_min, t_max);
    return first_only && n > 1 ? 1 : n;
}

/// surface_at() for a shape hit in object space: `normal(p, part)` is the outward normal (any
/// length) at object point p; world N = Ng = its image by the inverse transpose, normalised.
template <class Normal>
inline SurfacePoint surface_from_object_normal(const Shape& s, const Ray& r, const Hit& hit,
                                               const Normal& normal) {
    const Ray ro = s.transform.to_object(r);
    const Vec3 p = ro.at(hit.t);
    SurfacePoint sp;
    sp.P = r.at(hit.t);
    sp.N = unit_or(s.transform.normal(normal(p, hit.part)), {0, 0, 1});
    sp.Ng = sp.N;
    return sp;
}

}  // namespace luz::shapes
