// Disc caps at a height z (cylinder ends, cone base, a frustum's top disc): their ray hits in
// object space and their tessellation as a fan sharing the side's rim vertices.
#pragma once

#include <cstdint>

#include "geometry/shapes/emitter.h"
#include "geometry/shapes/object_space.h"

namespace luz::shapes {

/// Cap discs are accepted up to this much beyond r² = 1, so that a ray through the rim never
/// slips between side (z test) and cap (r test) by rounding.
constexpr double cap_slack = 1e-9;

/// Offers the hits of object ray (o, d) with the unit disc at z = 0 (part_cap0) and, if `both`,
/// the disc of radius² `top_r2` at z = 1 (part_cap1).
inline void hit_caps(const D3& o, const D3& d, bool both, Nearest& n, double top_r2 = 1.0) {
    if (d.z == 0) return;
    for (int k = 0; k < (both ? 2 : 1); ++k) {
        const double t = (k - o.z) / d.z;
        const double x = o.x + t * d.x, y = o.y + t * d.y;
        const double r2 = k == 0 ? 1.0 : top_r2;
        if (x * x + y * y <= r2 + cap_slack) n.offer(t, k == 0 ? part_cap0 : part_cap1);
    }
}

/// A disc cap of radius r at height z, as a fan from its centre sharing the rim positions (the
/// same Circle values times r) of the side; `up` is the outward normal's direction.
inline void emit_cap(Emitter& e, const Circle& circle, float z, bool up, float r = 1.0f) {
    const int n = static_cast<int>(circle.c.size());
    const Vec3 nz{0, 0, up ? 1.0f : -1.0f};
    const uint32_t centre = e.vertex({0, 0, z}, nz);
    const uint32_t first = centre + 1;  // rim vertex j is first + j
    for (int j = 0; j < n; ++j) e.vertex({circle.c[j] * r, circle.s[j] * r, z}, nz);
    for (int j = 0; j < n; ++j) {
        const uint32_t a = first + j, b = first + (j + 1) % n;
        if (up)
            e.triangle(centre, a, b);
        else
            e.triangle(centre, b, a);
    }
}

/// The side between the rim of radius 1 at z = 0 and the rim of radius `k` at z = 1, one segment
/// along it, each vertex with the normal (cosφ, sinφ, m) (a cylinder: k = 1, m = 0); outward.
inline void emit_side(Emitter& e, const Circle& circle, float k = 1.0f, float m = 0.0f) {
    const int n = static_cast<int>(circle.c.size());
    uint32_t bottom = 0;
    for (int j = 0; j < n; ++j) {
        const Vec3 nr{circle.c[j], circle.s[j], m};
        const uint32_t b = e.vertex({circle.c[j], circle.s[j], 0}, nr);
        e.vertex({circle.c[j] * k, circle.s[j] * k, 1}, nr);
        if (j == 0) bottom = b;
    }
    // Vertex (j, 0) is bottom + 2j, (j, 1) is bottom + 2j + 1; φ̂ × ẑ points outwards.
    for (int j = 0; j < n; ++j) {
        const uint32_t a = bottom + 2 * j, b = bottom + 2 * ((j + 1) % n);
        e.quad(a, b, b + 1, a + 1);
    }
}

}  // namespace luz::shapes
