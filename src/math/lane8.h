// Eight-lane float and mask types for code that runs eight of something side by side (ray
// packets, the rasterizer's rows, shading eight points): GCC vector extensions, AVX where the
// build has it, two SSE2 halves otherwise; every operation is the IEEE one of the scalar code,
// lane by lane.
#pragma once

#include <cstdint>
#include <cstring>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

// Eight-lane values passed by value between inline functions: without AVX GCC notes that their
// ABI differs from an AVX build's; they never cross a library boundary.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace luz {

inline constexpr int kPacketLanes = 8;

/// Eight floats, eight 32-bit masks (all bits set where true), lane by lane.
typedef float Lane8f __attribute__((vector_size(32)));
typedef int32_t Lane8i __attribute__((vector_size(32)));

/// x in every lane (its bits: a −0 stays −0).
[[gnu::always_inline]] inline Lane8f lanes(float x) { return Lane8f{x, x, x, x, x, x, x, x}; }
/// The same type at any 4-byte-aligned address, of any type (one unaligned load or store: a
/// std::memcpy of several of them goes through the stack).
typedef float Lane8fUnaligned __attribute__((vector_size(32), aligned(4), may_alias));
/// Eight floats at p (32 bytes of any 4-byte-aligned object), and back.
[[gnu::always_inline]] inline Lane8f load_lanes(const void* p) {
    return *static_cast<const Lane8fUnaligned*>(p);
}
inline void store_lanes(void* p, Lane8f v) { *static_cast<Lane8fUnaligned*>(p) = v; }
/// Eight floats at a 32-byte-aligned p (one aligned load).
[[gnu::always_inline]] inline Lane8f load_aligned_lanes(const float* p) {
    return *reinterpret_cast<const Lane8f*>(p);
}

/// What this build's eight lanes do in one instruction, for code that picks its algorithm by
/// it: eight floats in one register (AVX; else two halves), eight 32-bit integers compared and
/// their minima and maxima taken in one (AVX2), a·b + c with one rounding (FMA).
#if defined(__AVX__)
inline constexpr bool kLane8InOneRegister = true;
#else
inline constexpr bool kLane8InOneRegister = false;
#endif
#if defined(__AVX2__)
inline constexpr bool kLane8iInOneRegister = true;
#else
inline constexpr bool kLane8iInOneRegister = false;
#endif
#if defined(__AVX2__) && defined(__FMA__)
inline constexpr bool kLaneFusedMultiplyAdd = true;
#else
inline constexpr bool kLaneFusedMultiplyAdd = false;
#endif

// Without AVX, GCC 12 compiles the comparisons of eight-lane vectors, their `?:` and some of
// their shuffles lane by lane, with scalar compares, branches and stores. The lane code
// therefore compares with lane_lt() … lane_ne() and selects with lane_select(): on an SSE2
// build they work on the vector's two 16-byte halves (one instruction each), with AVX they are
// the operators themselves. Arithmetic and bitwise operators compile well on either.
#if defined(__SSE2__) && !defined(__AVX__)
#define LUZ_LANE8_HALVES 1
namespace lane8_detail {
struct HalvesF {
    __m128 lo, hi;
};
struct HalvesI {
    __m128i lo, hi;
};
[[gnu::always_inline]] inline HalvesF halves(Lane8f a) {
    HalvesF h;
    std::memcpy(&h, &a, sizeof h);
    return h;
}
[[gnu::always_inline]] inline HalvesI halves(Lane8i a) {
    HalvesI h;
    std::memcpy(&h, &a, sizeof h);
    return h;
}
template <class V, class H>
[[gnu::always_inline]] inline V whole(H lo, H hi) {
    V v;
    std::memcpy(&v, &lo, sizeof lo);
    std::memcpy(reinterpret_cast<char*>(&v) + sizeof lo, &hi, sizeof hi);
    return v;
}
/// op(a, b) on each half of two float vectors, as a mask.
template <class Op>
[[gnu::always_inline]] inline Lane8i compare(Lane8f a, Lane8f b, Op op) {
    const HalvesF x = halves(a), y = halves(b);
    return whole<Lane8i>(op(x.lo, y.lo), op(x.hi, y.hi));
}
template <class Op>
[[gnu::always_inline]] inline Lane8i compare(Lane8i a, Lane8i b, Op op) {
    const HalvesI x = halves(a), y = halves(b);
    return whole<Lane8i>(op(x.lo, y.lo), op(x.hi, y.hi));
}
}  // namespace lane8_detail
#endif

/// a < b, a <= b, a > b, a >= b, a == b, a != b lane by lane, as masks (IEEE: only != holds
/// for a NaN).
[[gnu::always_inline]] inline Lane8i lane_lt(Lane8f a, Lane8f b) {
#if defined(LUZ_LANE8_HALVES)
    return lane8_detail::compare(a, b, [](__m128 x, __m128 y) { return _mm_cmplt_ps(x, y); });
#else
    return a < b;
#endif
}
[[gnu::always_inline]] inline Lane8i lane_le(Lane8f a, Lane8f b) {
#if defined(LUZ_LANE8_HALVES)
    return lane8_detail::compare(a, b, [](__m128 x, __m128 y) { return _mm_cmple_ps(x, y); });
#else
    return a <= b;
#endif
}
[[gnu::always_inline]] inline Lane8i lane_gt(Lane8f a, Lane8f b) { return lane_lt(b, a); }
[[gnu::always_inline]] inline Lane8i lane_ge(Lane8f a, Lane8f b) { return lane_le(b, a); }
[[gnu::always_inline]] inline Lane8i lane_eq(Lane8f a, Lane8f b) {
#if defined(LUZ_LANE8_HALVES)
    return lane8_detail::compare(a, b, [](__m128 x, __m128 y) { return _mm_cmpeq_ps(x, y); });
#else
    return a == b;
#endif
}
[[gnu::always_inline]] inline Lane8i lane_ne(Lane8f a, Lane8f b) {
#if defined(LUZ_LANE8_HALVES)
    return lane8_detail::compare(a, b, [](__m128 x, __m128 y) { return _mm_cmpneq_ps(x, y); });
#else
    return a != b;
#endif
}
/// The same for 32-bit integers.
[[gnu::always_inline]] inline Lane8i lane_lt(Lane8i a, Lane8i b) {
#if defined(LUZ_LANE8_HALVES)
    return lane8_detail::compare(a, b, [](__m128i x, __m128i y) { return _mm_cmplt_epi32(x, y); });
#else
    return a < b;
#endif
}
[[gnu::always_inline]] inline Lane8i lane_gt(Lane8i a, Lane8i b) { return lane_lt(b, a); }
[[gnu::always_inline]] inline Lane8i lane_ge(Lane8i a, Lane8i b) { return ~lane_lt(a, b); }
[[gnu::always_inline]] inline Lane8i lane_le(Lane8i a, Lane8i b) { return ~lane_lt(b, a); }
[[gnu::always_inline]] inline Lane8i lane_eq(Lane8i a, Lane8i b) {
#if defined(LUZ_LANE8_HALVES)
    return lane8_detail::compare(a, b, [](__m128i x, __m128i y) { return _mm_cmpeq_epi32(x, y); });
#else
    return a == b;
#endif
}
[[gnu::always_inline]] inline Lane8i lane_ne(Lane8i a, Lane8i b) { return ~lane_eq(a, b); }
/// x in every lane.
[[gnu::always_inline]] inline Lane8i lanes_i(int32_t x) { return Lane8i{} + x; }

/// Bit k set where lane k of `m` is true.
[[gnu::always_inline]] inline unsigned lane_bits(Lane8i m) {
#if defined(__AVX__)
    return static_cast<unsigned>(_mm256_movemask_ps((__m256)m));
#elif defined(__SSE2__)
    const lane8_detail::HalvesI h = lane8_detail::halves(m);
    return static_cast<unsigned>(_mm_movemask_ps(_mm_castsi128_ps(h.lo)) |
                                 (_mm_movemask_ps(_mm_castsi128_ps(h.hi)) << 4));
#else
    unsigned bits = 0;
    for (int k = 0; k < kPacketLanes; ++k) bits |= (m[k] != 0 ? 1u : 0u) << k;
    return bits;
#endif
}
/// The lanes of `mask` as a mask vector.
[[gnu::always_inline]] inline Lane8i lane_mask(unsigned mask) {
    const Lane8i bit = {1, 2, 4, 8, 16, 32, 64, 128};
    return lane_ne(lanes_i(static_cast<int32_t>(mask)) & bit, Lane8i{});
}

/// √x lane by lane (IEEE, as std::sqrt).
[[gnu::always_inline]] inline Lane8f lane_sqrt(Lane8f x) {
#if defined(__AVX__)
    return (Lane8f)_mm256_sqrt_ps((__m256)x);
#elif defined(__SSE2__)  // the two halves, each in one register
    const lane8_detail::HalvesF h = lane8_detail::halves(x);
    return lane8_detail::whole<Lane8f>(_mm_sqrt_ps(h.lo), _mm_sqrt_ps(h.hi));
#else
    for (int k = 0; k < kPacketLanes; ++k) x[k] = __builtin_sqrtf(x[k]);
    return x;
#endif
}
/// mask ? a : b lane by lane (`mask` all bits set or clear in each lane): one blend with AVX.
[[gnu::always_inline]] inline Lane8f lane_select(Lane8i mask, Lane8f a, Lane8f b) {
#if defined(__AVX__)
    return (Lane8f)_mm256_blendv_ps((__m256)b, (__m256)a, (__m256)mask);
#else
    return (Lane8f)(((Lane8i)a & mask) | ((Lane8i)b & ~mask));
#endif
}
[[gnu::always_inline]] inline Lane8i lane_select(Lane8i mask, Lane8i a, Lane8i b) {
#if defined(__AVX__)
    return (Lane8i)_mm256_blendv_ps((__m256)b, (__m256)a, (__m256)mask);
#else
    return (a & mask) | (b & ~mask);
#endif
}
/// a > b ? a : b lane by lane, b where either is NaN (one maxps; the slab tests' running
/// maximum, which a NaN leaves as it is).
[[gnu::always_inline]] inline Lane8f greater_or_second(Lane8f a, Lane8f b) {
#if defined(__AVX__)
    return (Lane8f)_mm256_max_ps((__m256)a, (__m256)b);
#elif defined(__SSE2__)
    const lane8_detail::HalvesF x = lane8_detail::halves(a), y = lane8_detail::halves(b);
    return lane8_detail::whole<Lane8f>(_mm_max_ps(x.lo, y.lo), _mm_max_ps(x.hi, y.hi));
#else
    return lane_select(lane_gt(a, b), a, b);
#endif
}
/// a < b ? a : b lane by lane, b where either is NaN (one minps).
[[gnu::always_inline]] inline Lane8f less_or_second(Lane8f a, Lane8f b) {
#if defined(__AVX__)
    return (Lane8f)_mm256_min_ps((__m256)a, (__m256)b);
#elif defined(__SSE2__)
    const lane8_detail::HalvesF x = lane8_detail::halves(a), y = lane8_detail::halves(b);
    return lane8_detail::whole<Lane8f>(_mm_min_ps(x.lo, y.lo), _mm_min_ps(x.hi, y.hi));
#else
    return lane_select(lane_lt(a, b), a, b);
#endif
}
/// std::max(a, b), std::min(a, b) of 32-bit integers lane by lane (one instruction with AVX2).
[[gnu::always_inline]] inline Lane8i lane_max(Lane8i a, Lane8i b) {
#if defined(__AVX2__)
    return (Lane8i)_mm256_max_epi32((__m256i)a, (__m256i)b);
#else
    return lane_select(lane_lt(a, b), b, a);
#endif
}
[[gnu::always_inline]] inline Lane8i lane_min(Lane8i a, Lane8i b) {
#if defined(__AVX2__)
    return (Lane8i)_mm256_min_epi32((__m256i)a, (__m256i)b);
#else
    return lane_select(lane_lt(b, a), b, a);
#endif
}
/// a·b + c lane by lane with one rounding (std::fma; one instruction with FMA).
[[gnu::always_inline]] inline Lane8f lane_fmadd(Lane8f a, Lane8f b, Lane8f c) {
#if defined(__AVX2__) && defined(__FMA__)
    return (Lane8f)_mm256_fmadd_ps((__m256)a, (__m256)b, (__m256)c);
#else
    for (int k = 0; k < kPacketLanes; ++k) c[k] = __builtin_fmaf(a[k], b[k], c[k]);
    return c;
#endif
}
/// |x|, |x| with the sign of s, std::min(a, b) and std::max(a, b) lane by lane, as math/lane4.h's.
[[gnu::always_inline]] inline Lane8f lane_abs(Lane8f x) {
    return (Lane8f)((Lane8i)x & lanes_i(0x7FFFFFFF));
}
[[gnu::always_inline]] inline Lane8f lane_copysign(Lane8f x, Lane8f s) {
    const Lane8i sign = lanes_i(INT32_MIN);
    return (Lane8f)(((Lane8i)x & ~sign) | ((Lane8i)s & sign));
}
[[gnu::always_inline]] inline Lane8f lane_min(Lane8f a, Lane8f b) { return less_or_second(b, a); }
[[gnu::always_inline]] inline Lane8f lane_max(Lane8f a, Lane8f b) {
    return greater_or_second(b, a);
}

/// base[index[k]] in lane k.
[[gnu::always_inline]] inline Lane8i gather_lanes(const int32_t* base, Lane8i index) {
#if defined(__AVX2__)
    return (Lane8i)_mm256_i32gather_epi32(base, (__m256i)index, 4);
#else
    Lane8i v;
    for (int k = 0; k < kPacketLanes; ++k) v[k] = base[index[k]];
    return v;
#endif
}

}  // namespace luz
