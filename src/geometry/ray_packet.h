// RayPacket: up to eight rays side by side (one per lane), for the packet kernels (their lane
// types: math/lane8.h).
#pragma once

#include <cstdint>
#include <cstring>

#include "math/lane8.h"
#include "math/ray.h"

namespace luz {

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
