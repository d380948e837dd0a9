// The OpenEXR files luz writes (image/exr_codec.cpp): ZIP float scanlines from 0, read back bit
// for bit at every size, raw chunks where ZIP does not shrink, and accepted by exrheader.
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
#include "same_bits.h"
#include "temp_dir.h"

namespace luz {
namespace {

using test::awkward_image;
using test::box;
using test::channel;
using test::TempDir;

/// The header of `bytes`, read with OpenEXRCore.
struct Header {
    exr_storage_t storage{};
    exr_compression_t compression{};
    exr_attr_box2i_t data_window{}, display_window{};
    std::vector<std::pair<std::string, exr_pixel_type_t>> channels;
};

int64_t read_from_view(exr_const_context_t, void* user, void* buffer, uint64_t size,
                       uint64_t offset, exr_stream_error_func_ptr_t) {
    const std::string_view in = *static_cast<std::string_view*>(user);
    if (offset >= in.size()) return 0;
    const uint64_t n = std::min<uint64_t>(size, in.size() - offset);
    std::memcpy(buffer, in.data() + offset, n);
    return static_cast<int64_t>(n);
}

Header header_of(std::string_view bytes) {
    Header h;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.user_data = &bytes;
    init.read_fn = &read_from_view;
    exr_context_t ctxt = nullptr;
    EXPECT_EQ(exr_start_read(&ctxt, "luz", &init), EXR_ERR_SUCCESS);
    if (ctxt == nullptr) return h;
    EXPECT_EQ(exr_get_storage(ctxt, 0, &h.storage), EXR_ERR_SUCCESS);
    EXPECT_EQ(exr_get_compression(ctxt, 0, &h.compression), EXR_ERR_SUCCESS);
    EXPECT_EQ(exr_get_data_window(ctxt, 0, &h.data_window), EXR_ERR_SUCCESS);
    EXPECT_EQ(exr_get_display_window(ctxt, 0, &h.display_window), EXR_ERR_SUCCESS);
    const exr_attr_chlist_t* list = nullptr;
    EXPECT_EQ(exr_get_channels(ctxt, 0, &list), EXR_ERR_SUCCESS);
    for (int i = 0; list != nullptr && i < list->num_channels; ++i) {
        h.channels.emplace_back(list->entries[i].name.str, list->entries[i].pixel_type);
    }
    exr_finish(&ctxt);
    return h;
}

TEST(ExrCodec, LuzWritesZipFloatScanlinesFromZero) {
    const Image img = awkward_image(21, 35, 1);
    const Image normal = awkward_image(21, 35, 2), depth = awkward_image(21, 35, 3);
    const std::string bytes =
        encode_exr_layers(img, {{"normal", &normal, false}, {"depth", &depth, true}});
    const Header h = header_of(bytes);
    EXPECT_EQ(h.storage, EXR_STORAGE_SCANLINE);
    EXPECT_EQ(h.compression, EXR_COMPRESSION_ZIP);
    for (const exr_attr_box2i_t& box : {h.data_window, h.display_window}) {
        EXPECT_EQ(box.min.x, 0);
        EXPECT_EQ(box.min.y, 0);
        EXPECT_EQ(box.max.x, 20);
        EXPECT_EQ(box.max.y, 34);
    }
    const std::vector<std::pair<std::string, exr_pixel_type_t>> channels = {
        {"B", EXR_PIXEL_FLOAT},       {"G", EXR_PIXEL_FLOAT},        {"R", EXR_PIXEL_FLOAT},
        {"depth.Y", EXR_PIXEL_FLOAT}, {"normal.B", EXR_PIXEL_FLOAT}, {"normal.G", EXR_PIXEL_FLOAT},
        {"normal.R", EXR_PIXEL_FLOAT}};
    EXPECT_EQ(h.channels, channels);

    // Every bit comes back, in every layer (a scalar layer holds its image's first channel).
    EXPECT_TRUE(same_bits(decode_exr(bytes), img));
    EXPECT_TRUE(same_bits(decode_exr_layer(bytes, "normal"), normal));
    Image depth_y = depth;
    for (Rgb& p : depth_y.pixels) p = Rgb{p.x};
    EXPECT_TRUE(same_bits(decode_exr_layer(bytes, "depth"), depth_y));
}

TEST(ExrCodec, RoundTripsEverySizeBitForBit) {
    // Chunk boundaries (16 lines), single rows and columns, compressible and incompressible.
    for (const auto& [w, h] : {std::pair{1, 1}, {1, 17}, {17, 1}, {3, 16}, {5, 33}, {64, 48}}) {
        for (uint32_t seed : {7u, 8u}) {
            Image img = awkward_image(w, h, seed);
            if (seed == 8) {  // smooth: compresses
                for (int y = 0; y < h; ++y) {
                    for (int x = 0; x < w; ++x) img.at(x, y) = Rgb{x * 0.25f, y * 0.5f, -1.0f};
                }
            }
            SCOPED_TRACE(::testing::Message() << w << "x" << h << " seed " << seed);
            EXPECT_TRUE(same_bits(decode_exr(encode_exr(img)), img));
        }
    }
}

/// The stored size of the chunk of line `y` of the scanline file `bytes`.
uint64_t chunk_size(std::string_view bytes, int y) {
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.user_data = &bytes;
    init.read_fn = &read_from_view;
    exr_context_t ctxt = nullptr;
    EXPECT_EQ(exr_start_read(&ctxt, "luz", &init), EXR_ERR_SUCCESS);
    exr_chunk_info_t cinfo{};
    EXPECT_EQ(exr_read_scanline_chunk_info(ctxt, 0, y, &cinfo), EXR_ERR_SUCCESS);
    exr_finish(&ctxt);
    return cinfo.packed_size;
}

TEST(ExrCodec, StoresRawAChunkThatZipDoesNotShrink) {
    // 16 x 1 pixels, 39 floats of random bits then zeros: zlib (1.2.13, level 6) makes the 192
    // bytes of the chunk 192 bytes again, which OpenEXRCore 3.1.5 would keep compressed and
    // every reader would take for raw. Stored raw, they read back (with any zlib).
    Image img(16, 1);
    std::mt19937 rng(1234);
    float* values = &img.pixels[0].x;
    for (int i = 0; i < 39; ++i) {
        const uint32_t bits = rng();
        std::memcpy(values + i, &bits, 4);
    }
    const std::string bytes = encode_exr(img);
    EXPECT_LE(chunk_size(bytes, 0), 192u);
    EXPECT_TRUE(same_bits(decode_exr(bytes), img));
}

TEST(ExrCodec, RefusesALayerOfAnotherSize) {
    const Image img(4, 3), other(3, 4);
    try {
        encode_exr_layers(img, {{"normal", &other, false}});
        FAIL() << "no error";
    } catch (const ImageError& e) {
        EXPECT_STREQ(e.what(), "EXR layer normal is not the image's size");
    }
}

TEST(ExrCodec, ExrheaderAcceptsWhatLuzWrites) {
    if (std::system("command -v exrheader > /dev/null 2>&1") != 0) {
        GTEST_SKIP() << "exrheader not installed (Debian package openexr)";
    }
    TempDir dir;
    const Image img = awkward_image(40, 30, 5), normal = awkward_image(40, 30, 6);
    {
        const std::string bytes = encode_exr_layers(img, {{"normal", &normal, false}});
        std::ofstream(dir / "x.exr", std::ios::binary) << bytes;
    }
    const std::string out = dir / "header.txt";
    ASSERT_EQ(std::system(("exrheader " + (dir / "x.exr") + " > " + out + " 2>&1").c_str()), 0);
    std::FILE* f = std::fopen(out.c_str(), "rb");
    ASSERT_NE(f, nullptr);
    std::string text(1 << 16, '\0');
    text.resize(std::fread(text.data(), 1, text.size(), f));
    std::fclose(f);
    EXPECT_NE(text.find("zip, multi-scanline blocks"), std::string::npos) << text;
    EXPECT_NE(text.find("normal.R, 32-bit floating-point"), std::string::npos) << text;
    EXPECT_NE(text.find("(0 0) - (39 29)"), std::string::npos) << text;
}

}  // namespace
}  // namespace luz
