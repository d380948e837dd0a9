// Scene ray queries by testing every shape (bounding box first, then the shape itself).
#include "geometry/scene_query.h"

#include <algorithm>
#include <cmath>

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

Vec3 inverse_direction(const Vec3& d) { return {1.0f / d.x, 1.0f / d.y, 1.0f / d.z}; }

}  // namespace

bool nearest_hit(const Scene& scene, const Ray& r, float t_min, float t_max, Hit& hit,
                 IntersectCounters& counters) {
    const Vec3 inv_dir = inverse_direction(r.direction);
    bool found = false;
    for (size_t i = 0; i < scene.shapes.size(); ++i) {
        const Shape& s = scene.shapes[i];
        if (is_bounded(s)) {
            ++counters.bounds;
            if (!hit_bounds(scene.bounds[i], r, inv_dir, t_min, t_max)) continue;
        }
        ++counters.primitive;
        if (intersect(s, r, t_min, t_max, hit)) {
            hit.shape = static_cast<int>(i);
            t_max = hit.t;
            found = true;
        }
    }
    return found;
}

float transmittance(const Scene& scene, const Ray& r, float t_min, float t_max,
                    IntersectCounters& counters) {
    const Vec3 inv_dir = inverse_direction(r.direction);
    float T = 1.0f;
    for (size_t i = 0; i < scene.shapes.size(); ++i) {
        const Shape& s = scene.shapes[i];
        if (is_bounded(s)) {
            ++counters.bounds;
            if (!hit_bounds(scene.bounds[i], r, inv_dir, t_min, t_max)) continue;
        }
        const float transparency = scene.desc.materials[s.material].transparency;
        // Every crossing of this shape's surface along the segment, in order.
        Hit hit;
        float t = t_min;
        for (int crossings = 0; crossings < 64; ++crossings) {
            ++counters.primitive;
            if (!intersect(s, r, t, t_max, hit)) break;
            if (transparency <= 0) return 0.0f;
            T *= transparency;
            // Step past this crossing (relative step: the same root is not found twice).
            t = hit.t + 1e-4f * std::max(1.0f, hit.t);
        }
    }
    return T;
}

}  // namespace luz
