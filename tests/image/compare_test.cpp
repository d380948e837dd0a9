// Tests for the image comparison helpers (compare.h).

#include "image/compare.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace luz {
namespace {

TEST(CompareImages, IdenticalImages) {
    const Image a(4, 3, Rgb{0.1f, 0.2f, 0.3f});
    const ImageDiff d = compare_images(a, a);
    EXPECT_TRUE(d.same_size);
    EXPECT_EQ(d.max_abs, 0.0);
    EXPECT_EQ(d.rmse, 0.0);
    EXPECT_EQ(d.pixels, 12u);
    EXPECT_EQ(d.pixels_above, 0u);
    EXPECT_EQ(d.max_x, -1);
    EXPECT_EQ(d.fraction_within(), 1.0);
    EXPECT_EQ(to_string(d), "identical (12 pixels)");
}

TEST(CompareImages, OneChannelOff) {
    Image a(4, 4, Rgb{0.5f}), b = a;
    b.at(3, 1).y = 0.75f;
    const ImageDiff d = compare_images(a, b, 0.1f);
    EXPECT_EQ(d.max_abs, 0.25);
    EXPECT_EQ(d.max_x, 3);
    EXPECT_EQ(d.max_y, 1);
    EXPECT_EQ(d.max_channel, 1);
    EXPECT_DOUBLE_EQ(d.rmse, std::sqrt(0.25 * 0.25 / 48.0));
    EXPECT_EQ(d.pixels_above, 1u);
    EXPECT_DOUBLE_EQ(d.fraction_within(), 15.0 / 16.0);
    EXPECT_EQ(to_string(d),
              "max |a-b| 0.25 at (3, 1) channel G, rmse 0.0360844, 1 of 16 pixels above 0.1");

    EXPECT_EQ(max_abs_difference(a, b), 0.25);
    EXPECT_EQ(max_abs_difference(b, a), 0.25);
    EXPECT_DOUBLE_EQ(rms_difference(a, b), d.rmse);
    EXPECT_DOUBLE_EQ(fraction_within(a, b, 0.1f), 15.0 / 16.0);
    EXPECT_EQ(fraction_within(a, b, 0.25f), 1.0);  // at most tol counts as within
}

TEST(CompareImages, FractionCountsPixelsNotChannels) {
    Image a(2, 1), b(2, 1);
    b.at(0, 0) = Rgb{0.5f, 0.5f, 0.5f};  // three channels off in one pixel
    EXPECT_DOUBLE_EQ(fraction_within(a, b, 0.1f), 0.5);
}

TEST(CompareImages, DifferentSizes) {
    const Image a(4, 3), b(3, 4);
    const ImageDiff d = compare_images(a, b);
    EXPECT_FALSE(d.same_size);
    EXPECT_TRUE(std::isinf(d.max_abs));
    EXPECT_TRUE(std::isinf(rms_difference(a, b)));
    EXPECT_EQ(fraction_within(a, b, 1.0f), 0.0);
    EXPECT_EQ(to_string(d), "images differ in size");
}

TEST(CompareImages, NanAndInfinity) {
    const float nan = std::nanf(""), inf = std::numeric_limits<float>::infinity();
    Image a(3, 1), b(3, 1);
    a.at(0, 0) = b.at(0, 0) = Rgb{nan, inf, -inf};  // equal to themselves
    EXPECT_EQ(max_abs_difference(a, b), 0.0);
    b.at(1, 0).x = nan;  // NaN against a number
    EXPECT_TRUE(std::isinf(max_abs_difference(a, b)));
    EXPECT_DOUBLE_EQ(fraction_within(a, b, 1e9f), 2.0 / 3.0);
}

TEST(CompareImages, EmptyImagesAreEqual) {
    EXPECT_EQ(max_abs_difference(Image(), Image()), 0.0);
    EXPECT_EQ(fraction_within(Image(), Image(), 0.0f), 1.0);
}

}  // namespace
}  // namespace luz
