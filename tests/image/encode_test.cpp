// Tests for format_from_path and encode_8bit (docs/CLI.md: output formats, 8-bit encodings).

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>

#include "image/image_io.h"

namespace luz {
namespace {

ImageFormat format_of(const std::string& path) {
    ImageFormat f{};
    EXPECT_TRUE(format_from_path(path, f)) << path;
    return f;
}

bool known(const std::string& path) {
    ImageFormat f{};
    return format_from_path(path, f);
}

TEST(FormatFromPath, KnowsTheFourExtensions) {
    EXPECT_EQ(format_of("a.png"), ImageFormat::png);
    EXPECT_EQ(format_of("a.ppm"), ImageFormat::ppm);
    EXPECT_EQ(format_of("a.pfm"), ImageFormat::pfm);
    EXPECT_EQ(format_of("a.exr"), ImageFormat::exr);
    EXPECT_EQ(format_of("out/dir.v2/render.final.exr"), ImageFormat::exr);
}

TEST(FormatFromPath, IsCaseInsensitive) {
    EXPECT_EQ(format_of("A.PNG"), ImageFormat::png);
    EXPECT_EQ(format_of("a.PpM"), ImageFormat::ppm);
    EXPECT_EQ(format_of("a.Pfm"), ImageFormat::pfm);
    EXPECT_EQ(format_of("a.EXR"), ImageFormat::exr);
}

TEST(FormatFromPath, RejectsOtherNames) {
    EXPECT_FALSE(known("a.jpg"));
    EXPECT_FALSE(known("a.png.bak"));
    EXPECT_FALSE(known("png"));
    EXPECT_FALSE(known("a"));
    EXPECT_FALSE(known("a."));
    EXPECT_FALSE(known("dir.png/file"));  // the dot belongs to a directory
    EXPECT_FALSE(known(""));
}

TEST(FormatFromPath, LeavesOutputAloneWhenUnknown) {
    ImageFormat f = ImageFormat::exr;
    EXPECT_FALSE(format_from_path("a.tiff", f));
    EXPECT_EQ(f, ImageFormat::exr);
}

TEST(Encode8bitLinear, HandValues) {
    // round(255·clamp(I, 0, 1))
    EXPECT_EQ(encode_8bit(0.0f, Encoding::linear), 0);
    EXPECT_EQ(encode_8bit(1.0f, Encoding::linear), 255);
    EXPECT_EQ(encode_8bit(0.5f, Encoding::linear), 128);   // 127.5 rounds up
    EXPECT_EQ(encode_8bit(0.25f, Encoding::linear), 64);   // 63.75
    EXPECT_EQ(encode_8bit(0.1f, Encoding::linear), 26);    // 25.5000004
    EXPECT_EQ(encode_8bit(0.45f, Encoding::linear), 115);  // 114.75
    EXPECT_EQ(encode_8bit(1.0f / 255.0f, Encoding::linear), 1);
    EXPECT_EQ(encode_8bit(0.4f / 255.0f, Encoding::linear), 0);
    EXPECT_EQ(encode_8bit(0.6f / 255.0f, Encoding::linear), 1);
    EXPECT_EQ(encode_8bit(254.4f / 255.0f, Encoding::linear), 254);
    EXPECT_EQ(encode_8bit(254.6f / 255.0f, Encoding::linear), 255);
}

TEST(Encode8bitLinear, EveryLevelIsItsOwnCode) {
    for (int v = 0; v <= 255; ++v) {
        EXPECT_EQ(encode_8bit(static_cast<float>(v) / 255.0f, Encoding::linear), v);
    }
}

TEST(Encode8bitLinear, ClampsAndMapsNanToZero) {
    const float inf = std::numeric_limits<float>::infinity();
    EXPECT_EQ(encode_8bit(-0.5f, Encoding::linear), 0);
    EXPECT_EQ(encode_8bit(-0.0f, Encoding::linear), 0);
    EXPECT_EQ(encode_8bit(1.5f, Encoding::linear), 255);
    EXPECT_EQ(encode_8bit(1000.0f, Encoding::linear), 255);
    EXPECT_EQ(encode_8bit(inf, Encoding::linear), 255);
    EXPECT_EQ(encode_8bit(-inf, Encoding::linear), 0);
    EXPECT_EQ(encode_8bit(std::nanf(""), Encoding::linear), 0);
    EXPECT_EQ(encode_8bit(-std::nanf(""), Encoding::linear), 0);
}

TEST(Encode8bitSrgb, HandValues) {
    EXPECT_EQ(encode_8bit(0.0f, Encoding::srgb), 0);
    EXPECT_EQ(encode_8bit(1.0f, Encoding::srgb), 255);
    EXPECT_EQ(encode_8bit(0.5f, Encoding::srgb),
              188);  // 1.055·0.5^(1/2.4) − 0.055 = 0.7354 → 187.52
    EXPECT_EQ(encode_8bit(0.18f, Encoding::srgb), 118);  // 117.65
    EXPECT_EQ(encode_8bit(0.002f, Encoding::srgb), 7);   // linear segment: 12.92·0.002·255 = 6.59
    EXPECT_EQ(encode_8bit(0.0031308f, Encoding::srgb), 10);  // the knee: 10.31
    EXPECT_EQ(encode_8bit(0.01f, Encoding::srgb), 25);       // 25.46
    EXPECT_EQ(encode_8bit(0.214f, Encoding::srgb), 127);     // 127.49
    EXPECT_EQ(encode_8bit(0.216f, Encoding::srgb), 128);     // 128.04
}

TEST(Encode8bitSrgb, ClampsAndMapsNanToZero) {
    EXPECT_EQ(encode_8bit(-0.2f, Encoding::srgb), 0);
    EXPECT_EQ(encode_8bit(2.0f, Encoding::srgb), 255);
    EXPECT_EQ(encode_8bit(std::numeric_limits<float>::infinity(), Encoding::srgb), 255);
    EXPECT_EQ(encode_8bit(std::nanf(""), Encoding::srgb), 0);
}

TEST(Encode8bitSrgb, IsMonotoneAndReachesEveryCode) {
    // The curve is continuous at the knee and increasing, so a fine sweep hits all 256 codes.
    std::set<int> seen;
    int previous = 0;
    for (int i = 0; i <= 1 << 18; ++i) {
        const int v = encode_8bit(static_cast<float>(i) / (1 << 18), Encoding::srgb);
        ASSERT_GE(v, previous) << i;
        previous = v;
        seen.insert(v);
    }
    EXPECT_EQ(seen.size(), 256u);
}

TEST(Encode8bitSrgb, BrightensMidtonesComparedToLinear) {
    for (float I : {0.01f, 0.1f, 0.3f, 0.6f, 0.9f}) {
        EXPECT_GT(encode_8bit(I, Encoding::srgb), encode_8bit(I, Encoding::linear)) << I;
    }
}

}  // namespace
}  // namespace luz
