// Four-lane float and mask types, as math/lane8.h's eight: GCC vector extensions, one SSE2
// register where the build has it; every operation the IEEE one of the scalar code, lane by
// lane (sphere groups, the scene BVH's blocks of four triangles, the wide BVH's slab test).
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
/// Two doubles (the few steps computed in double, lane by lane).
typedef double Lane2d __attribute__((vector_size(16)));

/// x in every lane.
[[gnu::always_inline]] inline Lane4f lanes4(float x) { return Lane4f{x, x, x, x}; }
[[gnu::always_inline]] inline Lane4i lanes4_i(int32_t x) { return Lane4i{x, x, x, x}; }
[[gnu::always_inline]] inline Lane2d lanes2d(double x) { return Lane2d{x, x}; }

/// The same type at any 4-byte-aligned address, of any type.
typedef float Lane4fUnaligned __attribute__((vector_size(16), aligned(4), may_alias));
/// Four floats at p (16 bytes of any 4-byte-aligned object), and back.
[[gnu::always_inline]] inline Lane4f load_lanes4(const float* p) {
    return *reinterpret_cast<const Lane4fUnaligned*>(p);
}
[[gnu::always_inline]] inline void store_lanes4(float* p, Lane4f v) {
    *reinterpret_cast<Lane4fUnaligned*>(p) = v;
}
/// Four floats at a 16-byte-aligned p (one aligned load).
[[gnu::always_inline]] inline Lane4f load_aligned_lanes4(const float* p) {
    return *reinterpret_cast<const Lane4f*>(p);
}

/// The comparisons of math/lane8.h for four lanes (the operators: GCC compiles them well here),
/// so that code written for either lane type (ray_triangle.h) compares alike.
[[gnu::always_inline]] inline Lane4i lane_lt(Lane4f a, Lane4f b) { return a < b; }
[[gnu::always_inline]] inline Lane4i lane_le(Lane4f a, Lane4f b) { return a <= b; }
[[gnu::always_inline]] inline Lane4i lane_gt(Lane4f a, Lane4f b) { return a > b; }
[[gnu::always_inline]] inline Lane4i lane_ge(Lane4f a, Lane4f b) { return a >= b; }
[[gnu::always_inline]] inline Lane4i lane_eq(Lane4f a, Lane4f b) { return a == b; }
[[gnu::always_inline]] inline Lane4i lane_ne(Lane4f a, Lane4f b) { return a != b; }
/// Bit k set where lane k of `m` is true (where its sign bit is set).
[[gnu::always_inline]] inline unsigned lane_bits(Lane4i m) {
#if defined(__SSE2__)
    return static_cast<unsigned>(_mm_movemask_ps((__m128)m));
#else
    unsigned bits = 0;
    for (int k = 0; k < 4; ++k) bits |= (m[k] < 0 ? 1u : 0u) << k;
    return bits;
#endif
}

/// mask ? a : b lane by lane (`mask` all bits set or clear in each lane).
[[gnu::always_inline]] inline Lane4f lane_select(Lane4i mask, Lane4f a, Lane4f b) {
    return (Lane4f)(((Lane4i)a & mask) | ((Lane4i)b & ~mask));
}
/// √x lane by lane (IEEE, as std::sqrt).
[[gnu::always_inline]] inline Lane4f lane_sqrt(Lane4f x) {
#if defined(__SSE2__)
    return (Lane4f)_mm_sqrt_ps((__m128)x);
#else
    for (int k = 0; k < 4; ++k) x[k] = __builtin_sqrtf(x[k]);
    return x;
#endif
}
/// |x| lane by lane (the sign bit cleared, as std::fabs).
[[gnu::always_inline]] inline Lane4f lane_abs(Lane4f x) {
    return (Lane4f)((Lane4i)x & lanes4_i(0x7FFFFFFF));
}
/// |x| with the sign of s, lane by lane (std::copysign).
[[gnu::always_inline]] inline Lane4f lane_copysign(Lane4f x, Lane4f s) {
    const Lane4i sign = lanes4_i(INT32_MIN);
    return (Lane4f)(((Lane4i)x & ~sign) | ((Lane4i)s & sign));
}
/// a > b ? a : b lane by lane, b where either is NaN (one maxps).
[[gnu::always_inline]] inline Lane4f greater_or_second(Lane4f a, Lane4f b) {
#if defined(__SSE2__)
    return (Lane4f)_mm_max_ps((__m128)a, (__m128)b);
#else
    return lane_select(lane_gt(a, b), a, b);
#endif
}
/// a < b ? a : b lane by lane, b where either is NaN (one minps).
[[gnu::always_inline]] inline Lane4f less_or_second(Lane4f a, Lane4f b) {
#if defined(__SSE2__)
    return (Lane4f)_mm_min_ps((__m128)a, (__m128)b);
#else
    return lane_select(lane_lt(a, b), a, b);
#endif
}
/// std::min(a, b) lane by lane: b < a ? b : a (a where either is NaN; a for −0 against +0).
[[gnu::always_inline]] inline Lane4f lane_min(Lane4f a, Lane4f b) { return less_or_second(b, a); }
/// std::max(a, b) lane by lane: a < b ? b : a (a where either is NaN).
[[gnu::always_inline]] inline Lane4f lane_max(Lane4f a, Lane4f b) {
    return greater_or_second(b, a);
}

/// Lanes 0, 1 (low) or 2, 3 (high) of x in double (exactly), and two pairs back in float
/// (rounded as a double's conversion to float is).
[[gnu::always_inline]] inline Lane2d lanes_low_double(Lane4f x) {
#if defined(__SSE2__)
    return (Lane2d)_mm_cvtps_pd((__m128)x);
#else
    return Lane2d{x[0], x[1]};
#endif
}
[[gnu::always_inline]] inline Lane2d lanes_high_double(Lane4f x) {
#if defined(__SSE2__)
    return (Lane2d)_mm_cvtps_pd(_mm_movehl_ps((__m128)x, (__m128)x));
#else
    return Lane2d{x[2], x[3]};
#endif
}
[[gnu::always_inline]] inline Lane4f lanes_float(Lane2d low, Lane2d high) {
#if defined(__SSE2__)
    return (Lane4f)_mm_movelh_ps(_mm_cvtpd_ps((__m128d)low), _mm_cvtpd_ps((__m128d)high));
#else
    return Lane4f{static_cast<float>(low[0]), static_cast<float>(low[1]),
                  static_cast<float>(high[0]), static_cast<float>(high[1])};
#endif
}

}  // namespace luz
