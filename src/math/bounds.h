// Bounds3: an axis-aligned bounding box, empty by default.
#pragma once

#include <limits>

#include "math/vec3.h"

namespace luz {

struct Bounds3 {
    Vec3 lo{std::numeric_limits<float>::infinity()};
    Vec3 hi{-std::numeric_limits<float>::infinity()};

    constexpr bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
    constexpr void expand(const Vec3& p) {
        lo = min(lo, p);
        hi = max(hi, p);
    }
    constexpr void expand(const Bounds3& b) {
        lo = min(lo, b.lo);
        hi = max(hi, b.hi);
    }
    constexpr Vec3 centre() const { return (lo + hi) * 0.5f; }
    constexpr Vec3 extent() const { return hi - lo; }
    /// The eight corners, bit k of the index choosing hi for axis k.
    constexpr Vec3 corner(int i) const {
        return {(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z};
    }
};

}  // namespace luz
