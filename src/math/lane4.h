// Four-lane float and mask types, as math/lane8.h's eight: GCC vector extensions on SSE2 lanes,
// every operation the IEEE one of the scalar code, lane by lane (the scene BVH's blocks of four
// triangles, geometry/prim_block.h).
#pragma once

#include <cstdint>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

// Four-lane values passed by value between inline functions (see math/lane8.h).
#pragma GCC diagnostic ignored "-Wpsabi"

namespace luz {

/// Four floats, four 32-bit masks (all bits set where true), lane by lane.
typedef float Lane4f __attribute__((vector_size(16)));
typedef int32_t Lane4i __attribute__((vector_size(16)));

/// x in every lane.
inline Lane4f lanes4(float x) { return Lane4f{x, x, x, x}; }
/// The comparisons of math/lane8.h for four lanes (the operators: GCC compiles them well here),
/// so that code written for either lane type (ray_triangle.h) compares alike.
inline Lane4i lane_lt(Lane4f a, Lane4f b) { return a < b; }
inline Lane4i lane_le(Lane4f a, Lane4f b) { return a <= b; }
inline Lane4i lane_gt(Lane4f a, Lane4f b) { return a > b; }
inline Lane4i lane_ge(Lane4f a, Lane4f b) { return a >= b; }
inline Lane4i lane_eq(Lane4f a, Lane4f b) { return a == b; }
inline Lane4i lane_ne(Lane4f a, Lane4f b) { return a != b; }
/// Bit k set where lane k of `m` is true.
inline unsigned lane_bits4(Lane4i m) {
#if defined(__SSE2__)
    return static_cast<unsigned>(_mm_movemask_ps((__m128)m));
#else
    unsigned bits = 0;
    for (int k = 0; k < 4; ++k) bits |= (m[k] != 0 ? 1u : 0u) << k;
    return bits;
#endif
}

}  // namespace luz
