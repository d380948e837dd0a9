// The lane functions of math/lanes.h that code writes once over float, double, Lane4f and Lane8f
// (ray_sphere.h, the wide BVH's slab test) against their scalar meaning, bit for bit on every
// pair of special values (±0, NaN, ±∞, denormals): lane_min/lane_max as std::min/std::max,
// greater_or_second/less_or_second as the slab tests' a > b ? a : b, lane_abs, lane_copysign,
// lane_sqrt, the integer minima and maxima, lane_fmadd as std::fma, the double round trip.
#include "math/lanes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace luz {
namespace {

std::vector<float> special_values() {
    const float inf = std::numeric_limits<float>::infinity();
    return {0.0f,
            -0.0f,
            1.0f,
            -1.0f,
            0.5f,
            1e-40f,
            -1e-40f,
            3e38f,
            -3e38f,
            inf,
            -inf,
            2.0f,
            -7.25f,
            std::numeric_limits<float>::quiet_NaN(),
            -std::numeric_limits<float>::quiet_NaN()};
}

uint32_t bits(float x) { return std::bit_cast<uint32_t>(x); }

/// Every (a, b) pair of special values, four (or eight) at a time in the lanes, with op and
/// its scalar meaning compared bit for bit.
template <class V, int N, class LaneOp, class ScalarOp>
void expect_pairs(LaneOp lane_op, ScalarOp scalar_op, const char* name) {
    const std::vector<float> v = special_values();
    std::vector<float> a, b;
    for (float x : v)
        for (float y : v) {
            a.push_back(x);
            b.push_back(y);
        }
    while (a.size() % N != 0) {
        a.push_back(1.0f);
        b.push_back(2.0f);
    }
    for (size_t first = 0; first < a.size(); first += N) {
        V x, y;
        for (int k = 0; k < N; ++k) {
            x[k] = a[first + k];
            y[k] = b[first + k];
        }
        const V r = lane_op(x, y);
        for (int k = 0; k < N; ++k)
            EXPECT_EQ(bits(r[k]), bits(scalar_op(x[k], y[k])))
                << name << "(" << x[k] << ", " << y[k] << ") lane " << k;
    }
}

template <class V, int N>
void expect_all_lane_functions() {
    expect_pairs<V, N>([](V a, V b) { return lane_min(a, b); },
                       [](float a, float b) { return std::min(a, b); }, "lane_min");
    expect_pairs<V, N>([](V a, V b) { return lane_max(a, b); },
                       [](float a, float b) { return std::max(a, b); }, "lane_max");
    // the scalar lanes too: the same meaning in every lane type
    expect_pairs<V, N>([](V a, V b) { return lane_min(a, b); },
                       [](float a, float b) { return lane_min(a, b); }, "lane_min (float)");
    expect_pairs<V, N>([](V a, V b) { return lane_max(a, b); },
                       [](float a, float b) { return lane_max(a, b); }, "lane_max (float)");
    expect_pairs<V, N>([](V a, V b) { return greater_or_second(a, b); },
                       [](float a, float b) { return a > b ? a : b; }, "greater_or_second");
    expect_pairs<V, N>([](V a, V b) { return less_or_second(a, b); },
                       [](float a, float b) { return a < b ? a : b; }, "less_or_second");
    expect_pairs<V, N>([](V a, V b) { return lane_copysign(a, b); },
                       [](float a, float b) { return std::copysign(a, b); }, "lane_copysign");
    expect_pairs<V, N>([](V a, V) { return lane_abs(a); },
                       [](float a, float) { return std::fabs(a); }, "lane_abs");
    expect_pairs<V, N>([](V a, V) { return lane_sqrt(a); },
                       [](float a, float) { return std::sqrt(a); }, "lane_sqrt");
}

TEST(Lanes, FourLaneFunctionsAreTheScalarOnesBitForBit) { expect_all_lane_functions<Lane4f, 4>(); }

TEST(Lanes, EightLaneFunctionsAreTheScalarOnesBitForBit) { expect_all_lane_functions<Lane8f, 8>(); }

TEST(Lanes, IntegerMinimaAndMaximaAndFusedMultiplyAdd) {
    const int32_t ints[] = {0, 1, -1, INT32_MIN, INT32_MAX, 7, -1000000, 123456789};
    for (int32_t x : ints) {
        for (int32_t y : ints) {
            const Lane8i a = lanes_i(x) + Lane8i{0, 1, 2, 3, 0, 0, 0, 0} * (x < INT32_MAX - 3);
            const Lane8i b = lanes_i(y);
            const Lane8i lo = lane_min(a, b), hi = lane_max(a, b);
            for (int k = 0; k < kPacketLanes; ++k) {
                EXPECT_EQ(lo[k], std::min(a[k], b[k]));
                EXPECT_EQ(hi[k], std::max(a[k], b[k]));
            }
        }
    }
    const std::vector<float> v = special_values();
    for (float x : v)
        for (float y : v) {
            const Lane8f r = lane_fmadd(
                lanes(x), lanes(y), Lane8f{0.0f, -0.0f, 1.0f, -1.0f, 1e-40f, 3e38f, 0.1f, -0.1f});
            for (int k = 0; k < kPacketLanes; ++k) {
                const float c[] = {0.0f, -0.0f, 1.0f, -1.0f, 1e-40f, 3e38f, 0.1f, -0.1f};
                const float want = std::fma(x, y, c[k]);
                if (std::isnan(want))
                    EXPECT_TRUE(std::isnan(r[k]));
                else
                    EXPECT_EQ(bits(r[k]), bits(want)) << x << "·" << y << " + " << c[k];
            }
        }
}

TEST(Lanes, DoubleHalvesRoundTripAsScalarConversions) {
    const Lane4f x{0.1f, -0.0f, 3e38f, 1e-40f};
    const Lane2d lo = lanes_low_double(x), hi = lanes_high_double(x);
    EXPECT_EQ(lo[0], static_cast<double>(x[0]));
    EXPECT_EQ(std::bit_cast<uint64_t>(lo[1]), std::bit_cast<uint64_t>(-0.0));
    EXPECT_EQ(hi[0], static_cast<double>(x[2]));
    EXPECT_EQ(hi[1], static_cast<double>(x[3]));
    const Lane2d a{1.0 / 3.0, 1e300}, b{-2.0 / 3.0, 1e-320};
    const Lane4f f = lanes_float(a, b);
    EXPECT_EQ(bits(f[0]), bits(static_cast<float>(a[0])));
    EXPECT_EQ(bits(f[1]), bits(static_cast<float>(a[1])));
    EXPECT_EQ(bits(f[2]), bits(static_cast<float>(b[0])));
    EXPECT_EQ(bits(f[3]), bits(static_cast<float>(b[1])));
    EXPECT_EQ(lane_bits(Lane4i{-1, 0, INT32_MIN, 5}), 0b0101u);
}

}  // namespace
}  // namespace luz
