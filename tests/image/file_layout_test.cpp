// The bytes of the files written (PFM and PPM headers, row order, PNG colour chunks), hand-made
// files read back (big-endian and grey PFM, PPM comments), and unreadable files.

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <cstring>

#include "image/image_io.h"
#include "temp_dir.h"

namespace luz {
namespace {

using test::put_file;
using test::slurp;
using test::TempDir;
using namespace std::string_literals;

/// The float32 stored little-endian at bytes[at].
float float_le(const std::string& bytes, size_t at) {
    uint32_t u = 0;
    for (int i = 3; i >= 0; --i) u = (u << 8) | static_cast<unsigned char>(bytes[at + i]);
    return std::bit_cast<float>(u);
}

/// 4 bytes of a float32 in the given byte order.
std::string float_bytes(float v, bool little_endian) {
    const uint32_t u = std::bit_cast<uint32_t>(v);
    std::string b(4, '\0');
    for (int i = 0; i < 4; ++i) {
        b[little_endian ? i : 3 - i] = static_cast<char>((u >> (8 * i)) & 0xff);
    }
    return b;
}

/// A 3x2 image whose every channel is distinct: (x, y, c) → 100y + 10x + c (+ 0.5).
Image distinct_pixels() {
    Image img(3, 2);
    for (int y = 0; y < 2; ++y) {
        for (int x = 0; x < 3; ++x) {
            img.at(x, y) = Rgb{100.0f * y + 10.0f * x + 0.5f, 100.0f * y + 10.0f * x + 1.5f,
                               100.0f * y + 10.0f * x + 2.5f};
        }
    }
    return img;
}

TEST(PfmFile, HeaderAndBottomUpLittleEndianRows) {
    TempDir dir;
    const Image img = distinct_pixels();
    write_image(dir / "x.pfm", img);
    const std::string bytes = slurp(dir / "x.pfm");
    const std::string header = "PF\n3 2\n-1.0\n";
    ASSERT_EQ(bytes.substr(0, header.size()), header);
    ASSERT_EQ(bytes.size(), header.size() + 3 * 2 * 12);
    // The first row in the file is the image's bottom row (y = 1).
    size_t at = header.size();
    for (int y = 1; y >= 0; --y) {
        for (int x = 0; x < 3; ++x) {
            for (int c = 0; c < 3; ++c, at += 4) {
                EXPECT_EQ(float_le(bytes, at), img.at(x, y)[c]) << x << "," << y << "," << c;
            }
        }
    }
}

TEST(PpmFile, HeaderAndTopDownRows) {
    TempDir dir;
    Image img(2, 2);
    img.at(0, 0) = Rgb{1.0f, 0.0f, 0.5f};
    img.at(1, 0) = Rgb{0.0f, 1.0f, 2.0f};
    img.at(0, 1) = Rgb{-1.0f, 10.0f / 255.0f, 0.25f};
    img.at(1, 1) = Rgb{std::nanf(""), 0.2f, 0.7f};
    write_image(dir / "x.ppm", img);
    const std::string expected =
        "P6\n2 2\n255\n"
        "\xff\x00\x80"    // 1, 0, 0.5 → 127.5 rounds up
        "\x00\xff\xff"    // clamped above 1
        "\x00\x0a\x40"    // clamped below 0; 10/255; 0.25 → 63.75
        "\x00\x33\xb2"s;  // NaN → 0; 0.2 → 51; 0.7f → 178.49999
    EXPECT_EQ(slurp(dir / "x.ppm"), expected);
}

TEST(PpmFile, SrgbEncodingIsApplied) {
    TempDir dir;
    write_image(dir / "x.ppm", Image(1, 1, Rgb{0.5f}), Encoding::srgb);
    EXPECT_EQ(slurp(dir / "x.ppm"), std::string("P6\n1 1\n255\n\xbc\xbc\xbc"));  // 188
}

bool has_chunk(const std::string& png, const char* type) {
    return png.find(type) != std::string::npos;
}

TEST(PngFile, ColourChunksFollowTheEncoding) {
    TempDir dir;
    const Image img(4, 4, Rgb{0.3f});
    write_image(dir / "lin.png", img, Encoding::linear);
    write_image(dir / "srgb.png", img, Encoding::srgb);
    const std::string lin = slurp(dir / "lin.png"), srgb = slurp(dir / "srgb.png");
    ASSERT_EQ(lin.substr(0, 8), "\x89PNG\r\n\x1a\n");
    // Linear files carry no colour tag: viewers show the values as they are.
    EXPECT_FALSE(has_chunk(lin, "sRGB"));
    EXPECT_FALSE(has_chunk(lin, "gAMA"));
    EXPECT_TRUE(has_chunk(srgb, "sRGB"));
    // IHDR: width 4, height 4, bit depth 8, colour type 2 (RGB).
    EXPECT_EQ(lin.substr(12, 4), "IHDR");
    EXPECT_EQ(lin.substr(16, 10), "\0\0\0\x04\0\0\0\x04\x08\x02"s);
}

TEST(ExrFile, StartsWithTheMagicNumber) {
    TempDir dir;
    write_image(dir / "x.exr", Image(2, 2, Rgb{0.5f}));
    EXPECT_EQ(slurp(dir / "x.exr").substr(0, 4), "\x76\x2f\x31\x01");
}

TEST(ReadPfm, BigEndianFile) {
    TempDir dir;
    // Scale +1.0: big-endian; rows bottom-up; extra whitespace is allowed in the header.
    std::string bytes = "PF\n2  1\n1.0\n";
    for (float v : {1.5f, -2.0f, 3.25f, 100.0f, 0.0f, -0.5f}) bytes += float_bytes(v, false);
    put_file(dir / "be.pfm", bytes);
    const Image img = read_image(dir / "be.pfm");
    ASSERT_EQ(img.width, 2);
    ASSERT_EQ(img.height, 1);
    EXPECT_EQ(img.at(0, 0), (Rgb{1.5f, -2.0f, 3.25f}));
    EXPECT_EQ(img.at(1, 0), (Rgb{100.0f, 0.0f, -0.5f}));
}

TEST(ReadPfm, GreyFileBottomUp) {
    TempDir dir;
    std::string bytes = "Pf\n1 3\n-2.5\n";  // the scale's size means nothing
    for (float v : {0.25f, 0.5f, 4.0f}) bytes += float_bytes(v, true);  // bottom row first
    put_file(dir / "grey.pfm", bytes);
    const Image img = read_image(dir / "grey.pfm");
    ASSERT_EQ(img.width, 1);
    ASSERT_EQ(img.height, 3);
    EXPECT_EQ(img.at(0, 2), Rgb{0.25f});
    EXPECT_EQ(img.at(0, 1), Rgb{0.5f});
    EXPECT_EQ(img.at(0, 0), Rgb{4.0f});
}

TEST(ReadPpm, CommentsAndOtherMaxvals) {
    TempDir dir;
    put_file(dir / "c.ppm", "P6\n# made by hand\n2 1 # size\n255\n\x00\x33\xff\x80\x01\x02"s);
    const Image a = read_image(dir / "c.ppm");
    ASSERT_EQ(a.width, 2);
    EXPECT_EQ(a.at(0, 0), (Rgb{0.0f, 0.2f, 1.0f}));
    EXPECT_EQ(a.at(1, 0), (Rgb{128 / 255.0f, 1 / 255.0f, 2 / 255.0f}));

    put_file(dir / "m.ppm", "P6 1 1 15\n\x0f\x05\x00"s);
    EXPECT_EQ(read_image(dir / "m.ppm").at(0, 0), (Rgb{1.0f, 5 / 15.0f, 0.0f}));

    put_file(dir / "w.ppm", "P6\n1 1\n65535\n\xff\xff\x80\x00\x00\x01"s);
    EXPECT_EQ(read_image(dir / "w.ppm").at(0, 0), (Rgb{1.0f, 32768 / 65535.0f, 1 / 65535.0f}));
}

TEST(ReadImage, ByContentWhateverTheExtension) {
    TempDir dir;
    write_image(dir / "x.pfm", Image(2, 1, Rgb{7.0f}));
    std::filesystem::rename(dir / "x.pfm", dir / "x.data");
    EXPECT_EQ(read_image(dir / "x.data").at(1, 0), Rgb{7.0f});
}

/// read_image(path) throws ImageError whose message names path and contains `what`.
void expect_read_error(const std::string& path, const std::string& what) {
    try {
        read_image(path);
        ADD_FAILURE() << "no error reading " << path;
    } catch (const ImageError& e) {
        const std::string msg = e.what();
        EXPECT_EQ(msg.rfind(path + ": ", 0), 0u) << msg;
        EXPECT_NE(msg.find(what), std::string::npos) << msg;
        EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    }
}

TEST(ReadImage, MissingFile) {
    TempDir dir;
    expect_read_error(dir / "nope.png", "No such file or directory");
}

TEST(ReadImage, DirectoryIsNotAnImage) {
    TempDir dir;
    expect_read_error(dir.path().string(), "cannot read");
}

TEST(ReadImage, UnknownContent) {
    TempDir dir;
    put_file(dir / "x.png", "hello, world");
    expect_read_error(dir / "x.png", "not a PNG, PPM, PFM or OpenEXR file");
    put_file(dir / "empty.pfm", "");
    expect_read_error(dir / "empty.pfm", "cannot read");
}

TEST(ReadImage, TruncatedFilesOfEveryFormat) {
    TempDir dir;
    const Image img(8, 8, Rgb{0.5f});
    for (const char* name : {"t.png", "t.ppm", "t.pfm", "t.exr"}) {
        const std::string path = dir / name;
        write_image(path, img);
        const std::string bytes = slurp(path);
        for (size_t keep : {bytes.size() / 2, bytes.size() - 1, size_t{12}}) {
            put_file(path, bytes.substr(0, keep));
            SCOPED_TRACE(std::string(name) + " cut to " + std::to_string(keep));
            expect_read_error(path, "cannot read");
        }
    }
}

TEST(ReadImage, BadHeaders) {
    TempDir dir;
    const std::pair<const char*, const char*> cases[] = {
        {"P6\n0 1\n255\n", "bad width"},
        {"P6\n1 -1\n255\n\1\2\3", "bad height"},
        {"P6\n1 1\n70000\n\1\2\3", "bad maxval"},
        {"P6\n99999999999 1\n255\n", "bad width"},
        {"P3\n1 1\n255\n1 2 3\n", "only binary PPM"},
        {"PF\n1 1\n0\n123456789012", "bad scale"},
        {"PF\n1 1\nabc\n123456789012", "bad scale"},
        {"PF\n1 1\n-1.0", "truncated"},
        {"PF\n100000 100000\n-1.0\n1234", "truncated"},
    };
    for (const auto& [content, what] : cases) {
        put_file(dir / "bad.img", content);
        SCOPED_TRACE(content);
        expect_read_error(dir / "bad.img", what);
    }
}

}  // namespace
}  // namespace luz
