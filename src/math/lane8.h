// Eight-lane float and mask types for code that runs eight of something side by side (ray
// packets, the rasterizer's rows, shading eight points): GCC vector extensions, AVX where the
// build has it, two SSE2 halves otherwise; every operation is the IEEE one of the scalar code,
// lane by lane.
#pragma once

#include <cstdint>

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
inline Lane8f lanes(float x) { return Lane8f{x, x, x, x, x, x, x, x}; }
/// The same type at any 4-byte-aligned address, of any type (one unaligned load or store: a
/// std::memcpy of several of them goes through the stack).
typedef float Lane8fUnaligned __attribute__((vector_size(32), aligned(4), may_alias));
/// Eight floats at p (32 bytes of any 4-byte-aligned object), and back.
inline Lane8f load_lanes(const void* p) { return *static_cast<const Lane8fUnaligned*>(p); }
inline void store_lanes(void* p, Lane8f v) { *static_cast<Lane8fUnaligned*>(p) = v; }
/// Bit k set where lane k of `m` is true.
inline unsigned lane_bits(Lane8i m) {
#if defined(__AVX__)
    return static_cast<unsigned>(_mm256_movemask_ps((__m256)m));
#elif defined(__SSE2__)
    const __m128 lo = (__m128)__builtin_shufflevector(m, m, 0, 1, 2, 3);
    const __m128 hi = (__m128)__builtin_shufflevector(m, m, 4, 5, 6, 7);
    return static_cast<unsigned>(_mm_movemask_ps(lo) | (_mm_movemask_ps(hi) << 4));
#else
    unsigned bits = 0;
    for (int k = 0; k < kPacketLanes; ++k) bits |= (m[k] != 0 ? 1u : 0u) << k;
    return bits;
#endif
}
/// The lanes of `mask` as a mask vector.
inline Lane8i lane_mask(unsigned mask) {
    const Lane8i bit = {1, 2, 4, 8, 16, 32, 64, 128};
    return ((Lane8i{} + static_cast<int32_t>(mask)) & bit) != 0;
}

/// √x lane by lane (IEEE, as std::sqrt).
inline Lane8f lane_sqrt(Lane8f x) {
#if defined(__AVX__)
    return (Lane8f)_mm256_sqrt_ps((__m256)x);
#elif defined(__SSE2__)  // the two halves, each in one register
    const __m128 lo = _mm_sqrt_ps((__m128)__builtin_shufflevector(x, x, 0, 1, 2, 3));
    const __m128 hi = _mm_sqrt_ps((__m128)__builtin_shufflevector(x, x, 4, 5, 6, 7));
    return (Lane8f)__builtin_shufflevector(lo, hi, 0, 1, 2, 3, 4, 5, 6, 7);
#else
    for (int k = 0; k < kPacketLanes; ++k) x[k] = __builtin_sqrtf(x[k]);
    return x;
#endif
}
/// mask ? a : b lane by lane (`mask` all bits set or clear in each lane).
inline Lane8f lane_select(Lane8i mask, Lane8f a, Lane8f b) {
    return (Lane8f)(((Lane8i)a & mask) | ((Lane8i)b & ~mask));
}
inline Lane8i lane_select(Lane8i mask, Lane8i a, Lane8i b) { return (a & mask) | (b & ~mask); }
/// base[index[k]] in lane k.
inline Lane8i gather_lanes(const int32_t* base, Lane8i index) {
#if defined(__AVX2__)
    return (Lane8i)_mm256_i32gather_epi32(base, (__m256i)index, 4);
#else
    Lane8i v;
    for (int k = 0; k < kPacketLanes; ++k) v[k] = base[index[k]];
    return v;
#endif
}

}  // namespace luz
