// Bit-for-bit image equality for tests: the same size and the same bytes in every channel, so
// NaN equals NaN and -0 differs from +0 (where image/compare.h's differences see no change).
#pragma once

#include <cstring>

#include "luz/image.h"

namespace luz {

inline bool same_bits(const Image& a, const Image& b) {
    return a.width == b.width && a.height == b.height && a.pixels.size() == b.pixels.size() &&
           std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(Rgb)) == 0;
}

}  // namespace luz
