// RayPacket: up to eight rays side by side (one per lane), and the eight-lane float and mask
// types the packet kernels compute with (GCC vector extensions: AVX where the build has it, two
// SSE2 halves otherwise; every operation is the IEEE one of the scalar code, lane by lane).
#pragma once

#include <cstdint>
#include <cstring>

#include "math/ray.h"

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace luz {

inline constexpr int kPacketLanes = 8;

/// Eight floats, eight 32-bit masks (all bits set where true), lane by lane.
typedef float Lane8f __attribute__((vector_size(32)));
typedef int32_t Lane8i __attribute__((vector_size(32)));

/// x in every lane (its bits: a −0 stays −0).
inline Lane8f lanes(float x) { return Lane8f{x, x, x, x, x, x, x, x}; }
inline Lane8f load_lanes(const float* p) {
    Lane8f v;
    std::memcpy(&v, p, sizeof v);
    return v;
}
/// Bit k set where lane k of `m` is true.
inline unsigned lane_bits(Lane8i m) {
#if defined(__AVX__)
    return static_cast<unsigned>(_mm256_movemask_ps((__m256)m));
#elif defined(__SSE2__)
    __m128 lo, hi;
    std::memcpy(&lo, &m, sizeof lo);
    std::memcpy(&hi, reinterpret_cast<const char*>(&m) + sizeof lo, sizeof hi);
    return static_cast<unsigned>(_mm_movemask_ps(lo) | (_mm_movemask_ps(hi) << 4));
#else
    unsigned bits = 0;
    for (int k = 0; k < kPacketLanes; ++k) bits |= (m[k] != 0 ? 1u : 0u) << k;
    return bits;
#endif
}
/// The lanes of `mask` as a mask vector.
inline Lane8i lane_mask(unsigned mask) {
    Lane8i m;
    for (int k = 0; k < kPacketLanes; ++k) m[k] = (mask >> k) & 1u ? -1 : 0;
    return m;
}

/// Rays in lanes 0 … n−1 (n ≤ 8), by component; lanes ≥ n copy lane 0 and are never active.
struct RayPacket {
    Lane8f o[3], d[3];
    int n = 0;

    RayPacket(const Ray* rays, int count) : n(count) {
        for (int k = 0; k < kPacketLanes; ++k) {
            const Ray& r = rays[k < count ? k : 0];
            for (int a = 0; a < 3; ++a) {
                o[a][k] = r.origin[a];
                d[a][k] = r.direction[a];
            }
        }
    }
    unsigned all() const { return (1u << n) - 1; }
};

}  // namespace luz
