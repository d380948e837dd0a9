// next_up(x): the next float above x, as std::nextafter(x, +∞) gives it, inline (the scene
// queries take it for every primitive a ray is offered, where a library call shows).
#pragma once

#include <bit>
#include <cstdint>
#include <limits>

namespace luz {

/// The smallest float greater than x; +∞ and NaN are returned as they are, −0 and +0 give the
/// smallest subnormal.
inline float next_up(float x) {
    if (!(x < std::numeric_limits<float>::infinity())) return x;
    if (x == 0.0f) return std::numeric_limits<float>::denorm_min();
    const uint32_t bits = std::bit_cast<uint32_t>(x);
    return std::bit_cast<float>(x > 0 ? bits + 1 : bits - 1);
}

}  // namespace luz
