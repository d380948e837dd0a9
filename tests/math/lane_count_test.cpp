// lane_count() against counting the bits one by one, for every mask of up to eight lanes.
#include "math/lane_count.h"

#include <gtest/gtest.h>

namespace luz {

TEST(LaneCount, CountsTheLanesOfEveryMaskOfEightLanes) {
    for (unsigned m = 0; m < 256; ++m) {
        unsigned n = 0;
        for (int bit = 0; bit < 8; ++bit) n += (m >> bit) & 1u;
        EXPECT_EQ(lane_count(m), n) << "mask " << m;
    }
}

}  // namespace luz
