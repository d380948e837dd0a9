// The OpenEXR codec (image/exr_codec.cpp, on OpenEXRCore) reading files luz does not write
// itself, made with OpenEXRCore: half, float and uint channels, tiles, data windows away from 0,
// every compression the library writes, subsampled and unread channels, layers.
#include <OpenEXR/openexr.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>
#include <new>
#include <random>
#include <string>
#include <vector>

#include "exr_fixtures.h"
#include "image/image_codecs.h"
#include "image/image_io.h"
#include "temp_dir.h"

namespace luz {
namespace {

using test::box;
using test::channel;
using test::error_of;
using test::expect_pixels;
using test::half_value;
using test::make_file;
using test::rgb;
using test::set_data_window;
using test::TestChannel;
using test::TestFile;

TEST(ExrCodec, ReadsHalfChannelsOfADataWindowAwayFromZero) {
    TestFile file;
    file.data_window = box(-7, 3, 29, 40);  // 37 x 38, chunks of 16 lines from y = 3
    file.channels = rgb(EXR_PIXEL_HALF);
    const std::string bytes = make_file(file);
    ASSERT_FALSE(HasFatalFailure());
    const Image img = decode_exr(bytes);
    expect_pixels(img, file, &file.channels[0], &file.channels[1], &file.channels[2]);
}

TEST(ExrCodec, ReadsTiledFilesWithPartialTiles) {
    for (exr_pixel_type_t type : {EXR_PIXEL_HALF, EXR_PIXEL_FLOAT, EXR_PIXEL_UINT}) {
        TestFile file;
        file.storage = EXR_STORAGE_TILED;
        file.tile_w = 8;
        file.tile_h = 6;
        file.data_window = box(5, -9, 27, 7);  // 23 x 17: 3 x 3 tiles, the last ones partial
        file.compression = EXR_COMPRESSION_PIZ;
        file.channels = rgb(type);
        file.channels.push_back(channel("A", EXR_PIXEL_HALF, 3));  // not read
        SCOPED_TRACE(type);
        const std::string bytes = make_file(file);
        ASSERT_FALSE(HasFatalFailure());
        expect_pixels(decode_exr(bytes), file, &file.channels[0], &file.channels[1],
                      &file.channels[2]);
    }
}

TEST(ExrCodec, ReadsATileLargerThanTheImage) {
    TestFile file;
    file.storage = EXR_STORAGE_TILED;
    file.tile_w = 64;
    file.tile_h = 32;
    file.data_window = box(100, 200, 110, 203);
    file.channels = rgb(EXR_PIXEL_FLOAT);
    const std::string bytes = make_file(file);
    ASSERT_FALSE(HasFatalFailure());
    expect_pixels(decode_exr(bytes), file, &file.channels[0], &file.channels[1], &file.channels[2]);
}

TEST(ExrCodec, ReadsEveryLosslessCompression) {
    for (exr_compression_t compression :
         {EXR_COMPRESSION_NONE, EXR_COMPRESSION_RLE, EXR_COMPRESSION_ZIPS, EXR_COMPRESSION_ZIP,
          EXR_COMPRESSION_PIZ, EXR_COMPRESSION_PXR24}) {
        for (exr_storage_t storage : {EXR_STORAGE_SCANLINE, EXR_STORAGE_TILED}) {
            // PXR24 rounds floats to 24 bits: half and uint channels only.
            for (exr_pixel_type_t type : {EXR_PIXEL_HALF, EXR_PIXEL_FLOAT, EXR_PIXEL_UINT}) {
                if (compression == EXR_COMPRESSION_PXR24 && type == EXR_PIXEL_FLOAT) continue;
                TestFile file;
                file.storage = storage;
                file.compression = compression;
                file.tile_w = 16;
                file.tile_h = 16;
                file.data_window = box(-3, -2, 36, 40);
                file.channels = rgb(type);
                SCOPED_TRACE(::testing::Message() << "compression " << compression << " storage "
                                                  << storage << " type " << type);
                const std::string bytes = make_file(file);
                ASSERT_FALSE(HasFatalFailure());
                expect_pixels(decode_exr(bytes), file, &file.channels[0], &file.channels[1],
                              &file.channels[2]);
            }
        }
    }
}

TEST(ExrCodec, ReadsLossyCompressionsApproximately) {
    for (exr_compression_t compression : {EXR_COMPRESSION_B44, EXR_COMPRESSION_B44A}) {
        TestFile file;
        file.compression = compression;
        file.channels = rgb(EXR_PIXEL_HALF);
        const std::string bytes = make_file(file);
        ASSERT_FALSE(HasFatalFailure());
        const Image img = decode_exr(bytes);
        ASSERT_EQ(img.width, 16);
        ASSERT_EQ(img.height, 10);
        for (int y = 0; y < 10; ++y) {
            for (int x = 0; x < 16; ++x) {
                EXPECT_NEAR(img.at(x, y).x, half_value(x, y, 0), 8.0) << x << ", " << y;
            }
        }
    }
}

TEST(ExrCodec, ReadsChunksStoredRawInACompressedFile) {
    // Writers store a chunk raw when compressing does not shrink it (with B44: every chunk of
    // float channels). Made here as an uncompressed tiled file relabelled B44 and B44A (tiles,
    // unlike scanline chunks, do not change with the compression).
    for (char compression : {char(EXR_COMPRESSION_B44), char(EXR_COMPRESSION_B44A)}) {
        TestFile file;
        file.storage = EXR_STORAGE_TILED;
        file.tile_w = 8;
        file.tile_h = 4;
        file.compression = EXR_COMPRESSION_NONE;
        file.data_window = box(-2, -3, 20, 30);
        file.channels = rgb(EXR_PIXEL_FLOAT);
        file.channels.push_back(channel("A", EXR_PIXEL_HALF, 3));
        std::string bytes = make_file(file);
        ASSERT_FALSE(HasFatalFailure());
        const std::string key("compression\0compression\0\1\0\0\0\0", 29);
        const size_t at = bytes.find(key);
        ASSERT_NE(at, std::string::npos);
        bytes[at + key.size() - 1] = compression;
        SCOPED_TRACE(::testing::Message() << "compression " << int(compression));
        expect_pixels(decode_exr(bytes), file, &file.channels[0], &file.channels[1],
                      &file.channels[2]);
    }
}

TEST(ExrCodec, ReadsDecreasingLineOrder) {
    TestFile file;
    file.line_order = EXR_LINEORDER_DECREASING_Y;
    file.data_window = box(0, 1, 20, 50);
    file.channels = rgb(EXR_PIXEL_FLOAT);
    const std::string bytes = make_file(file);
    ASSERT_FALSE(HasFatalFailure());
    expect_pixels(decode_exr(bytes), file, &file.channels[0], &file.channels[1], &file.channels[2]);
}

TEST(ExrCodec, MissingChannelsReadAsZero) {
    // B and G without R, a Z after them: R must read 0, not Z (and nothing may crash).
    TestFile file;
    file.channels = {channel("B", EXR_PIXEL_HALF, 2), channel("G", EXR_PIXEL_HALF, 1),
                     channel("Z", EXR_PIXEL_HALF, 5)};
    std::string bytes = make_file(file);
    ASSERT_FALSE(HasFatalFailure());
    expect_pixels(decode_exr(bytes), file, nullptr, &file.channels[1], &file.channels[0]);

    // B and R around another channel: G reads 0.
    file.channels = {channel("B", EXR_PIXEL_HALF, 2), channel("Q", EXR_PIXEL_HALF, 1),
                     channel("R", EXR_PIXEL_HALF, 0)};
    bytes = make_file(file);
    ASSERT_FALSE(HasFatalFailure());
    expect_pixels(decode_exr(bytes), file, &file.channels[2], nullptr, &file.channels[0]);

    // Float and half mixed, R alone of the three.
    file.channels = {channel("A", EXR_PIXEL_FLOAT, 3), channel("R", EXR_PIXEL_HALF, 0),
                     channel("Z", EXR_PIXEL_UINT, 5)};
    bytes = make_file(file);
    ASSERT_FALSE(HasFatalFailure());
    expect_pixels(decode_exr(bytes), file, &file.channels[1], nullptr, nullptr);
}

TEST(ExrCodec, LuminanceFillsTheThreeChannels) {
    // Y, with subsampled chroma that luz does not read; with one line a chunk (NONE, RLE,
    // ZIPS), every other chunk has no chroma (OpenEXRCore would then unpack Y as three
    // channels, were it read straight into the image).
    for (exr_compression_t compression :
         {EXR_COMPRESSION_NONE, EXR_COMPRESSION_RLE, EXR_COMPRESSION_ZIPS, EXR_COMPRESSION_ZIP,
          EXR_COMPRESSION_PIZ}) {
        TestFile file;
        file.compression = compression;
        file.data_window = box(-4, 2, 19, 41);
        file.channels = {channel("Y", EXR_PIXEL_HALF, 0), channel("RY", EXR_PIXEL_HALF, 1),
                         channel("BY", EXR_PIXEL_HALF, 2)};
        for (int c = 1; c <= 2; ++c) file.channels[c].x_sampling = file.channels[c].y_sampling = 2;
        SCOPED_TRACE(compression);
        const std::string bytes = make_file(file);
        ASSERT_FALSE(HasFatalFailure());
        const TestChannel& y = file.channels[0];
        expect_pixels(decode_exr(bytes), file, &y, &y, &y);
    }
    // The same with R and B full and G subsampled: G is refused, but R and B with a
    // subsampled channel read.
    TestFile file;
    file.compression = EXR_COMPRESSION_NONE;
    file.channels = rgb(EXR_PIXEL_HALF);
    file.channels.push_back(channel("C", EXR_PIXEL_HALF, 4));
    file.channels[3].y_sampling = 2;
    file.channels.erase(file.channels.begin() + 1);  // no G
    const std::string bytes = make_file(file);
    ASSERT_FALSE(HasFatalFailure());
    expect_pixels(decode_exr(bytes), file, &file.channels[0], nullptr, &file.channels[1]);
}

TEST(ExrCodec, RefusesSubsampledColourChannels) {
    TestFile file;
    file.channels = rgb(EXR_PIXEL_HALF);
    file.channels[1].x_sampling = 2;
    const std::string bytes = make_file(file);
    ASSERT_FALSE(HasFatalFailure());
    EXPECT_EQ(error_of(bytes),
              "invalid OpenEXR: channel G is subsampled (2x1), which luz does not read");
}

TEST(ExrCodec, ReadsLayers) {
    TestFile file;
    file.data_window = box(1, 1, 9, 12);
    file.channels = rgb(EXR_PIXEL_HALF);
    for (const TestChannel& c : rgb(EXR_PIXEL_FLOAT, "normal.")) file.channels.push_back(c);
    file.channels.push_back(channel("depth.Y", EXR_PIXEL_FLOAT, 7));
    const std::string bytes = make_file(file);
    ASSERT_FALSE(HasFatalFailure());
    const auto& ch = file.channels;
    expect_pixels(decode_exr_layer(bytes, ""), file, &ch[0], &ch[1], &ch[2]);
    expect_pixels(decode_exr_layer(bytes, "normal"), file, &ch[3], &ch[4], &ch[5]);
    expect_pixels(decode_exr_layer(bytes, "depth"), file, &ch[6], &ch[6], &ch[6]);
    EXPECT_EQ(error_of(bytes, "albedo"), "no albedo.R, albedo.G, albedo.B or albedo.Y channel");
}

TEST(ExrCodec, NamesWhatIsMissing) {
    TestFile file;
    file.channels = {channel("Z", EXR_PIXEL_FLOAT, 0)};
    const std::string bytes = make_file(file);
    ASSERT_FALSE(HasFatalFailure());
    EXPECT_EQ(error_of(bytes), "no R, G, B or Y channel");
    EXPECT_EQ(error_of("GIF89a"), "not an OpenEXR file");
    EXPECT_EQ(error_of(""), "not an OpenEXR file");
    EXPECT_EQ(error_of(std::string("\x76\x2f\x31\x01", 4)).rfind("invalid OpenEXR: ", 0), 0u);
}

TEST(ExrCodec, RefusesAnUncompressedChunkOfTheWrongSize) {
    // A data window made wider than the pixels stored: each chunk holds too few bytes.
    TestFile file;
    file.compression = EXR_COMPRESSION_NONE;
    file.channels = rgb(EXR_PIXEL_HALF);
    std::string bytes = make_file(file);
    ASSERT_FALSE(HasFatalFailure());
    set_data_window(bytes, 2, 1000);  // (0 0) - (15 9) becomes (0 0) - (1000 9)
    ASSERT_FALSE(HasFatalFailure());
    EXPECT_EQ(error_of(bytes), "invalid OpenEXR: the chunk at (0, 0) holds 96 bytes for 6006");
}

}  // namespace
}  // namespace luz
