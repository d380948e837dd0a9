// next_up() against std::nextafter(x, +∞) over signs, zeros, subnormals, normals, the largest
// float, infinities and NaN.
#include "math/next_float.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <limits>
#include <random>

namespace luz {
namespace {

TEST(NextFloat, NextUpIsNextafterTowardsInfinity) {
    using L = std::numeric_limits<float>;
    std::vector<float> xs = {
        0.0f,     -0.0f,     L::denorm_min(), -L::denorm_min(), L::min(), -L::min(), 1.0f, -1.0f,
        L::max(), -L::max(), L::infinity(),   -L::infinity(),   1e-40f,   -1e-40f,   3.5f, -2.0f};
    std::mt19937 rng(3);
    for (int k = 0; k < 100000; ++k)
        xs.push_back(std::bit_cast<float>(static_cast<uint32_t>(rng())));
    for (float x : xs) {
        const float want = std::nextafter(x, L::infinity()), got = next_up(x);
        if (std::isnan(x)) {
            EXPECT_TRUE(std::isnan(got));
        } else {
            EXPECT_EQ(std::bit_cast<uint32_t>(got), std::bit_cast<uint32_t>(want)) << x;
        }
    }
}

}  // namespace
}  // namespace luz
