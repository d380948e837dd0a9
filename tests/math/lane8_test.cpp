// The eight-lane helpers of math/lane8.h against their lane-by-lane meaning: masks to vectors and
// back for every mask, IEEE square roots, the comparisons (floats with NaN, ±0 and infinities;
// integers to the extremes) and selections, and loads and stores at any 4-byte-aligned address
// that touch exactly their 32 bytes.
#include "math/lane8.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

namespace luz {

TEST(Lane8, MaskVectorsAndBitsRoundTripForEveryMask) {
    for (unsigned m = 0; m < 256; ++m) {
        const Lane8i v = lane_mask(m);
        for (int k = 0; k < kPacketLanes; ++k)
            EXPECT_EQ(v[k], (m >> k) & 1u ? -1 : 0) << "mask " << m << " lane " << k;
        EXPECT_EQ(lane_bits(v), m);
    }
}

TEST(Lane8, SquareRootIsStdSqrtInEveryLaneBitForBit) {
    const float values[] = {0.0f,
                            -0.0f,
                            1.0f,
                            2.0f,
                            0.3f,
                            1e-40f,
                            3e38f,
                            -1.0f,
                            std::numeric_limits<float>::infinity(),
                            123.456f,
                            7.0e-6f,
                            0.5f,
                            std::numeric_limits<float>::quiet_NaN()};
    constexpr int n = sizeof values / sizeof values[0];
    for (int first = 0; first < n; ++first) {
        Lane8f x;
        for (int k = 0; k < kPacketLanes; ++k) x[k] = values[(first + k) % n];
        const Lane8f r = lane_sqrt(x);
        for (int k = 0; k < kPacketLanes; ++k) {
            const float expected = std::sqrt(x[k]);
            if (std::isnan(expected)) {
                EXPECT_TRUE(std::isnan(r[k])) << x[k];
            } else {
                EXPECT_EQ(std::bit_cast<uint32_t>(r[k]), std::bit_cast<uint32_t>(expected)) << x[k];
            }
        }
    }
}

TEST(Lane8, FloatComparisonsAreTheScalarOnesInEveryLane) {
    const float inf = std::numeric_limits<float>::infinity();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float values[] = {0.0f, -0.0f, 1.0f, -1.0f, 0.3f, 1e-40f, -3e38f, inf, -inf, nan, 2.5f};
    constexpr int n = sizeof values / sizeof values[0];
    const auto mask = [](bool b) { return b ? -1 : 0; };
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            Lane8f a, b;
            for (int k = 0; k < kPacketLanes; ++k) {  // every pair, in every lane
                a[k] = values[(i + k) % n];
                b[k] = values[(j + 3 * k) % n];
            }
            const Lane8i lt = lane_lt(a, b), le = lane_le(a, b), gt = lane_gt(a, b),
                         ge = lane_ge(a, b), eq = lane_eq(a, b), ne = lane_ne(a, b);
            const Lane8f min = lane_select(lt, a, b);
            const Lane8f greater = greater_or_second(a, b), less = less_or_second(a, b);
            for (int k = 0; k < kPacketLanes; ++k) {
                const float x = a[k], y = b[k];
                EXPECT_EQ(lt[k], mask(x < y)) << x << " < " << y;
                EXPECT_EQ(le[k], mask(x <= y)) << x << " <= " << y;
                EXPECT_EQ(gt[k], mask(x > y)) << x << " > " << y;
                EXPECT_EQ(ge[k], mask(x >= y)) << x << " >= " << y;
                EXPECT_EQ(eq[k], mask(x == y)) << x << " == " << y;
                EXPECT_EQ(ne[k], mask(x != y)) << x << " != " << y;
                EXPECT_EQ(std::bit_cast<uint32_t>(min[k]), std::bit_cast<uint32_t>(x < y ? x : y));
                EXPECT_EQ(std::bit_cast<uint32_t>(greater[k]),
                          std::bit_cast<uint32_t>(x > y ? x : y))
                    << x << " > " << y << " ? ...";
                EXPECT_EQ(std::bit_cast<uint32_t>(less[k]), std::bit_cast<uint32_t>(x < y ? x : y))
                    << x << " < " << y << " ? ...";
            }
        }
    }
}

TEST(Lane8, IntegerComparisonsAreTheScalarOnesInEveryLane) {
    const int32_t values[] = {0, 1, -1, 7, -7, INT32_MAX, INT32_MIN, 1 << 20, -(1 << 20)};
    constexpr int n = sizeof values / sizeof values[0];
    const auto mask = [](bool b) { return b ? -1 : 0; };
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            Lane8i a, b;
            for (int k = 0; k < kPacketLanes; ++k) {
                a[k] = values[(i + k) % n];
                b[k] = values[(j + 5 * k) % n];
            }
            const Lane8i lt = lane_lt(a, b), le = lane_le(a, b), gt = lane_gt(a, b),
                         ge = lane_ge(a, b), eq = lane_eq(a, b), ne = lane_ne(a, b);
            for (int k = 0; k < kPacketLanes; ++k) {
                const int32_t x = a[k], y = b[k];
                EXPECT_EQ(lt[k], mask(x < y)) << x << " < " << y;
                EXPECT_EQ(le[k], mask(x <= y)) << x << " <= " << y;
                EXPECT_EQ(gt[k], mask(x > y)) << x << " > " << y;
                EXPECT_EQ(ge[k], mask(x >= y)) << x << " >= " << y;
                EXPECT_EQ(eq[k], mask(x == y)) << x << " == " << y;
                EXPECT_EQ(ne[k], mask(x != y)) << x << " != " << y;
            }
        }
    }
    for (int k = 0; k < kPacketLanes; ++k) EXPECT_EQ(lanes_i(-42)[k], -42);
}

TEST(Lane8, LoadsAndStoresAtEveryFourByteOffsetTouchOnlyTheirBytes) {
    for (int offset = 0; offset < 8; ++offset) {
        alignas(32) float buffer[24];
        for (int i = 0; i < 24; ++i) buffer[i] = static_cast<float>(i);
        float* at = buffer + offset;
        const Lane8f v = load_lanes(at);
        for (int k = 0; k < kPacketLanes; ++k) EXPECT_EQ(v[k], static_cast<float>(offset + k));
        store_lanes(at, v * 2.0f);
        for (int i = 0; i < 24; ++i) {
            const bool inside = i >= offset && i < offset + kPacketLanes;
            EXPECT_EQ(buffer[i], static_cast<float>(inside ? 2 * i : i)) << "offset " << offset;
        }
    }
}

}  // namespace luz
