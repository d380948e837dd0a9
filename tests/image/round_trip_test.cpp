// Round trips through every format: 8-bit formats give back exactly encode_8bit(v)/255, float
// formats give back the very bits written (values above 1, negative, tiny, infinite, NaN).

#include <gtest/gtest.h>
#include <png.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>

#include "image/compare.h"
#include "image/image_io.h"
#include "same_bits.h"
#include "temp_dir.h"

namespace luz {
namespace {

using test::TempDir;

/// A non-square image with values in [0, 1] plus a row of out-of-range ones.
Image test_pattern(int w = 13, int h = 7) {
    Image img(w, h);
    std::mt19937 rng(42);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (Rgb& p : img.pixels) p = Rgb{u(rng), u(rng), u(rng)};
    // Exact codes, extremes and out-of-range values in the last row.
    const float extra[] = {0.0f, 1.0f, 0.5f, 1.0f / 255.0f, -0.25f, 1.75f, 250.0f, -3.0f};
    for (int x = 0; x < w; ++x) {
        img.at(x, h - 1) = Rgb{extra[x % 8], extra[(x + 3) % 8], extra[(x + 5) % 8]};
    }
    img.at(0, 0) = Rgb{1.0f, 0.0f, 0.0f};  // a corner to catch flips
    return img;
}

/// `img` as an 8-bit file holds it: each channel encode_8bit(v, e) / 255.
Image quantized(const Image& img, Encoding e) {
    Image q = img;
    for (Rgb& p : q.pixels) {
        for (int c = 0; c < 3; ++c) p[c] = static_cast<float>(encode_8bit(p[c], e)) / 255.0f;
    }
    return q;
}

class RoundTrip8 : public ::testing::TestWithParam<std::tuple<std::string, Encoding>> {};

TEST_P(RoundTrip8, GivesBackTheEncodedValues) {
    const auto& [ext, e] = GetParam();
    TempDir dir;
    const Image img = test_pattern();
    const std::string path = dir / ("img." + ext);
    write_image(path, img, e);
    const Image back = read_image(path);
    ASSERT_EQ(back.width, img.width);
    ASSERT_EQ(back.height, img.height);
    const Image expected = quantized(img, e);
    EXPECT_EQ(max_abs_difference(back, expected), 0.0) << to_string(compare_images(back, expected));
    if (e == Encoding::linear) {
        // Linear encoding loses at most half a code on in-range values.
        Image clamped = img;
        for (Rgb& p : clamped.pixels) p = clamp01(p);
        EXPECT_LE(max_abs_difference(back, clamped), 0.5 / 255.0 + 1e-6);
    }
    EXPECT_EQ(back.at(0, 0), (Rgb{1.0f, 0.0f, 0.0f}));
}

INSTANTIATE_TEST_SUITE_P(Formats, RoundTrip8,
                         ::testing::Combine(::testing::Values("png", "ppm"),
                                            ::testing::Values(Encoding::linear, Encoding::srgb)),
                         [](const auto& info) {
                             return std::get<0>(info.param) +
                                    (std::get<1>(info.param) == Encoding::srgb ? "_srgb"
                                                                               : "_linear");
                         });

class RoundTripFloat : public ::testing::TestWithParam<std::string> {};

TEST_P(RoundTripFloat, IsBitExactAndUnclamped) {
    TempDir dir;
    Image img = test_pattern(9, 5);
    const float inf = std::numeric_limits<float>::infinity();
    img.at(1, 1) = Rgb{1e30f, -1e-30f, 1e-40f};  // huge, tiny negative, denormal
    img.at(2, 1) = Rgb{inf, -inf, std::nanf("")};
    img.at(3, 1) = Rgb{-0.0f, 3.5f, -7.25f};
    const std::string path = dir / ("img." + GetParam());
    write_image(path, img, Encoding::srgb);  // the encoding does not apply to float formats
    const Image back = read_image(path);
    EXPECT_TRUE(same_bits(back, img)) << to_string(compare_images(back, img));
    EXPECT_EQ(back.at(3, 1).z, -7.25f);
    EXPECT_EQ(back.at(1, 1).x, 1e30f);
}

TEST_P(RoundTripFloat, OnePixel) {
    TempDir dir;
    const Image img(1, 1, Rgb{0.125f, 2.0f, -1.0f});
    const std::string path = dir / ("one." + GetParam());
    write_image(path, img);
    EXPECT_TRUE(same_bits(read_image(path), img));
}

TEST_P(RoundTripFloat, WideAndTall) {
    TempDir dir;
    for (const auto& [w, h] : {std::pair{301, 2}, std::pair{2, 301}}) {
        Image img(w, h);
        for (int y = 0; y < h; ++y) {
            for (int x = 0; x < w; ++x) img.at(x, y) = Rgb{float(x), float(y), float(x * y)};
        }
        const std::string path = dir / ("strip." + GetParam());
        write_image(path, img);
        EXPECT_TRUE(same_bits(read_image(path), img)) << w << "x" << h;
    }
}

INSTANTIATE_TEST_SUITE_P(Formats, RoundTripFloat, ::testing::Values("pfm", "exr"));

TEST(RoundTrip, UpperCaseExtensionsWork) {
    TempDir dir;
    const Image img = test_pattern(4, 3);
    for (const char* name : {"a.PNG", "b.PPM", "c.PFM", "d.EXR"}) {
        write_image(dir / name, img);
        EXPECT_EQ(read_image(dir / name).width, 4) << name;
    }
}

TEST(RoundTrip, LargeImage) {
    TempDir dir;
    Image img(640, 480);
    for (int y = 0; y < img.height; ++y) {
        for (int x = 0; x < img.width; ++x) {
            img.at(x, y) = Rgb{x / 639.0f, y / 479.0f, ((x ^ y) & 255) / 255.0f};
        }
    }
    for (const char* name : {"big.png", "big.ppm", "big.pfm", "big.exr"}) {
        write_image(dir / name, img);
        const Image back = read_image(dir / name);
        EXPECT_LE(max_abs_difference(back, img), 0.5 / 255.0 + 1e-6) << name;
    }
}

// PNG files that luz does not write itself: 8-bit RGBA (alpha dropped), 16-bit, grey.
void write_png_with_libpng(const std::string& path, png_uint_32 format, int w, int h,
                           const void* data) {
    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    image.width = static_cast<png_uint_32>(w);
    image.height = static_cast<png_uint_32>(h);
    image.format = format;
    ASSERT_TRUE(png_image_write_to_file(&image, path.c_str(), 0, data, 0, nullptr))
        << image.message;
}

TEST(ReadPng, Rgba8DropsAlpha) {
    TempDir dir;
    const unsigned char data[] = {255, 0, 10, 255, 20,  40,  60,  0,   // row 0
                                  1,   2, 3,  128, 200, 201, 202, 7};  // row 1
    write_png_with_libpng(dir / "rgba.png", PNG_FORMAT_RGBA, 2, 2, data);
    const Image img = read_image(dir / "rgba.png");
    ASSERT_EQ(img.width, 2);
    ASSERT_EQ(img.height, 2);
    EXPECT_EQ(img.at(0, 0), (Rgb{1.0f, 0.0f, 10 / 255.0f}));
    EXPECT_EQ(img.at(1, 0), (Rgb{20 / 255.0f, 40 / 255.0f, 60 / 255.0f}));
    EXPECT_EQ(img.at(0, 1), (Rgb{1 / 255.0f, 2 / 255.0f, 3 / 255.0f}));
    EXPECT_EQ(img.at(1, 1), (Rgb{200 / 255.0f, 201 / 255.0f, 202 / 255.0f}));
}

TEST(ReadPng, SixteenBit) {
    TempDir dir;
    const uint16_t data[] = {0, 65535, 32768, 1, 1000, 65534};
    write_png_with_libpng(dir / "deep.png", PNG_FORMAT_LINEAR_RGB, 2, 1, data);
    const Image img = read_image(dir / "deep.png");
    ASSERT_EQ(img.width, 2);
    EXPECT_EQ(img.at(0, 0), (Rgb{0.0f, 1.0f, 32768 / 65535.0f}));
    EXPECT_EQ(img.at(1, 0), (Rgb{1 / 65535.0f, 1000 / 65535.0f, 65534 / 65535.0f}));
}

TEST(ReadPng, GreyIsReplicated) {
    TempDir dir;
    const unsigned char data[] = {0, 51, 255};
    write_png_with_libpng(dir / "grey.png", PNG_FORMAT_GRAY, 3, 1, data);
    const Image img = read_image(dir / "grey.png");
    ASSERT_EQ(img.width, 3);
    EXPECT_EQ(img.at(1, 0), Rgb{0.2f});
    EXPECT_EQ(img.at(2, 0), Rgb{1.0f});
}

// PNG image data is deflated in parallel bands of 64 rows joined into one zlib stream: an
// image of many bands (and a last, partial one) reads back exactly (libpng checks the stream
// and its Adler-32), and its bytes do not depend on how many threads wrote it.
TEST(WritePng, ManyBandsRoundTripAndSameBytesOnOneThread) {
    const Image img = test_pattern(301, 200);  // 4 bands, the last of 8 rows
    for (Encoding e : {Encoding::linear, Encoding::srgb}) {
        const std::string bytes = encode_image("x.png", img, e);
        std::string one_thread;
        {
            tbb::global_control only(tbb::global_control::max_allowed_parallelism, 1);
            one_thread = encode_image("x.png", img, e);
        }
        EXPECT_EQ(bytes, one_thread);
        TempDir dir;
        const std::string path = dir / "img.png";
        write_image(path, img, e);
        EXPECT_TRUE(same_bits(read_image(path), quantized(img, e)));
    }
}

}  // namespace
}  // namespace luz

namespace luz {
namespace {

// Image(w, h, Unwritten): the right size, its pixels writable; large images start on a 2 MiB
// boundary (huge pages), small ones anywhere; filled images keep their fill.
TEST(ImageStorage, UnwrittenAndFilledImages) {
    Image big(1024, 1024, Unwritten{});  // 12 MiB
    ASSERT_EQ(big.pixels.size(), 1024u * 1024u);
    EXPECT_EQ(reinterpret_cast<uintptr_t>(big.pixels.data()) % (uintptr_t{2} << 20), 0u);
    for (Rgb& p : big.pixels) p = Rgb{0.25f};
    EXPECT_EQ(big.at(1023, 1023), Rgb{0.25f});
    const Image small(3, 2, Unwritten{});
    EXPECT_EQ(small.pixels.size(), 6u);
    const Image filled(5, 4, Rgb{0.5f, 0.25f, 1.0f});
    for (const Rgb& p : filled.pixels) EXPECT_EQ(p, (Rgb{0.5f, 0.25f, 1.0f}));
    const Image copy = filled;
    EXPECT_TRUE(same_bits(copy, filled));
}

// PngBands: an image given band by band, through one buffer of rows reused for each, makes the
// very bytes encode_image() makes of the whole image; rows given out of order are refused.
TEST(PngBands, BandByBandGivesTheBytesOfTheWholeImage) {
    const Image img = test_pattern(301, 200);  // bands of 128 rows: 128 + 72
    for (Encoding e : {Encoding::linear, Encoding::srgb}) {
        PngBands png(img.width, img.height, e);
        Image rows(img.width, 128, Rgb{-1.0f});
        for (int y0 = 0; y0 < img.height; y0 += 128) {
            const int n = std::min(128, img.height - y0);
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < img.width; ++x) rows.at(x, y) = img.at(x, y0 + y);
            png.add(rows, n);
        }
        EXPECT_EQ(png.finish(), encode_image("x.png", img, e));
    }
    PngBands early(301, 200, Encoding::linear);
    EXPECT_THROW(early.add(img, 100), ImageError);  // not a multiple of 64 rows, not the last
    early.add(img, 64);
    EXPECT_THROW(early.finish(), ImageError);       // rows missing
    EXPECT_THROW(early.add(img, 137), ImageError);  // beyond the image's 200 rows
    EXPECT_THROW(PngBands(300, 200, Encoding::linear).add(img, 64), ImageError);  // width
}

}  // namespace
}  // namespace luz
