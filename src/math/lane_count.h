// lane_count(): how many lanes a lane mask (one bit per lane, at most eight) has set, without
// the libgcc call __builtin_popcount becomes in the portable build (baseline x86-64 has no
// POPCNT instruction): the queries count their tests with it once per block or group.
#pragma once

namespace luz {

/// The bits set in m < 256.
inline unsigned lane_count(unsigned m) {
#if defined(__POPCNT__)
    return static_cast<unsigned>(__builtin_popcount(m));
#else
    m = m - ((m >> 1) & 0x55u);
    m = (m & 0x33u) + ((m >> 2) & 0x33u);
    return (m + (m >> 4)) & 0x0Fu;
#endif
}

}  // namespace luz
