// HugePageAllocator: arrays of 4 MiB and more 2 MiB-aligned (whole huge pages back them), smaller
// ones as their type asks; vectors built on it copy, grow and free like any vector. Whether the
// kernel gives huge pages is its choice (THP "never" refuses): that is reported, not required.
#include "math/huge_pages.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <numeric>
#include <string>
#include <vector>

namespace luz {
namespace {

using Floats = std::vector<float, HugePageAllocator<float>>;

bool aligned_to(const void* p, size_t alignment) {
    return reinterpret_cast<uintptr_t>(p) % alignment == 0;
}

TEST(HugePages, LargeArraysStartOnA2MiBBoundary) {
    Floats large(3 * kHugePage / sizeof(float));
    EXPECT_TRUE(aligned_to(large.data(), kHugePage));
    std::iota(large.begin(), large.end(), 0.0f);
    Floats copy = large;
    EXPECT_TRUE(aligned_to(copy.data(), kHugePage));
    EXPECT_EQ(copy, large);
    copy.resize(copy.size() + 1);  // regrows: a new aligned array, the contents kept
    EXPECT_TRUE(aligned_to(copy.data(), kHugePage));
    EXPECT_EQ(copy[12345], 12345.0f);

    struct alignas(64) Node {
        float x[16];
    };
    const std::vector<Node, HugePageAllocator<Node>> small(3);
    EXPECT_TRUE(aligned_to(small.data(), 64));

    // The kernel's answer, for the log: the process's huge pages now.
    std::ifstream smaps("/proc/self/smaps_rollup");
    for (std::string line; std::getline(smaps, line);)
        if (line.rfind("AnonHugePages:", 0) == 0) std::printf("%s\n", line.c_str());
}

TEST(HugePages, ACountWhoseBytesOverflowThrows) {
    HugePageAllocator<double> a;
    EXPECT_THROW(a.allocate(static_cast<size_t>(-1) / 4), std::bad_array_new_length);
}

}  // namespace
}  // namespace luz
