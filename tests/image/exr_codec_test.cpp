// The OpenEXR codec (image/exr_codec.cpp, on OpenEXRCore): files luz does not write itself, made
// here with OpenEXRCore — half, float and uint channels, tiles, data windows away from 0, every
// compression the library writes, subsampled and unread channels — and truncated or corrupt
// files, which must give an ImageError (never a crash, a hang or a line on stderr); and luz's
// own files, read back bit for bit and accepted by exrheader.

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

#include "image/image_codecs.h"
#include "image/image_io.h"
#include "temp_dir.h"

namespace luz {
namespace {

using test::TempDir;

// ---- Writing test files with OpenEXRCore ---------------------------------------------------

/// A channel of a test file: its value at pixel (x, y) of the data window (absolute
/// coordinates), exactly representable in its type.
struct TestChannel {
    std::string name;
    exr_pixel_type_t type = EXR_PIXEL_FLOAT;
    std::function<float(int, int)> value;
    int x_sampling = 1, y_sampling = 1;
};

exr_attr_box2i_t box(int x0, int y0, int x1, int y1) {
    exr_attr_box2i_t b{};
    b.min.x = x0;
    b.min.y = y0;
    b.max.x = x1;
    b.max.y = y1;
    return b;
}

struct TestFile {
    exr_storage_t storage = EXR_STORAGE_SCANLINE;
    exr_compression_t compression = EXR_COMPRESSION_ZIP;
    exr_lineorder_t line_order = EXR_LINEORDER_INCREASING_Y;
    exr_attr_box2i_t data_window = box(0, 0, 15, 9);
    int tile_w = 0, tile_h = 0;  // tiled files
    std::vector<TestChannel> channels;
};

int64_t write_to_string(exr_const_context_t, void* user, const void* buffer, uint64_t size,
                        uint64_t offset, exr_stream_error_func_ptr_t) {
    std::string& out = *static_cast<std::string*>(user);
    if (offset + size > out.size()) out.resize(offset + size);
    std::memcpy(out.data() + offset, buffer, size);
    return static_cast<int64_t>(size);
}

void quiet(exr_const_context_t, exr_result_t, const char*) {}

#define EXR_CHECK(call) ASSERT_EQ((call), EXR_ERR_SUCCESS) << #call

using Compress = exr_result_t (*)(exr_encode_pipeline_t*);
Compress library_compress = nullptr;

/// A chunk that compressing does not shrink is stored raw, as OpenEXR's C++ library does:
/// OpenEXRCore 3.1.5 keeps one of exactly its raw size compressed, which readers take for raw
/// data, and B44 chunks larger than raw, which it then refuses to read.
exr_result_t compress_or_store(exr_encode_pipeline_t* encode) {
    const exr_result_t rv = library_compress(encode);
    if (rv == EXR_ERR_SUCCESS && encode->compressed_bytes >= encode->packed_bytes &&
        encode->compressed_buffer != encode->packed_buffer) {
        std::memcpy(encode->compressed_buffer, encode->packed_buffer, encode->packed_bytes);
        encode->compressed_bytes = encode->packed_bytes;
    }
    return rv;
}

/// Encodes one chunk (its pixels from x0, y0) of `file` through the library's pipeline.
void write_chunk(exr_context_t ctxt, const TestFile& file, const exr_chunk_info_t& cinfo, int x0,
                 int y0, exr_encode_pipeline_t& encode, bool first) {
    if (first) {
        EXR_CHECK(exr_encoding_initialize(ctxt, 0, &cinfo, &encode));
    } else {
        EXR_CHECK(exr_encoding_update(ctxt, 0, &cinfo, &encode));
    }
    // One planar buffer per channel, its samples only: floats, or uint32 for UINT channels.
    std::vector<std::vector<uint32_t>> planes(encode.channel_count);
    for (int c = 0; c < encode.channel_count; ++c) {
        exr_coding_channel_info_t& ch = encode.channels[c];
        const TestChannel* tc = nullptr;
        for (const TestChannel& t : file.channels) {
            if (t.name == ch.channel_name) tc = &t;
        }
        ASSERT_NE(tc, nullptr);
        std::vector<uint32_t>& plane = planes[c];
        int rows = 0;
        for (int y = y0; y < y0 + cinfo.height; ++y) {
            if (y % tc->y_sampling != 0) continue;
            ++rows;
            for (int x = x0; x < x0 + cinfo.width; x += tc->x_sampling) {
                const float v = tc->value(x, y);
                uint32_t bits = 0;
                if (tc->type == EXR_PIXEL_UINT) {
                    bits = static_cast<uint32_t>(v);
                } else {
                    std::memcpy(&bits, &v, 4);
                }
                plane.push_back(bits);
            }
        }
        ASSERT_EQ(rows, ch.height) << ch.channel_name;
        ASSERT_EQ(plane.size(), size_t(ch.width) * size_t(ch.height)) << ch.channel_name;
        if (plane.empty()) plane.push_back(0);
        ch.encode_from_ptr = reinterpret_cast<const uint8_t*>(plane.data());
        ch.user_pixel_stride = 4;
        ch.user_line_stride = 4 * ch.width;
        ch.user_bytes_per_element = 4;
        ch.user_data_type = tc->type == EXR_PIXEL_UINT ? EXR_PIXEL_UINT : EXR_PIXEL_FLOAT;
    }
    if (first) {
        EXR_CHECK(exr_encoding_choose_default_routines(ctxt, 0, &encode));
        if (encode.compress_fn != nullptr) {
            library_compress = encode.compress_fn;
            encode.compress_fn = &compress_or_store;
        }
    }
    EXR_CHECK(exr_encoding_run(ctxt, 0, &encode));
}

void write_file(const TestFile& file, std::string& out) {
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.user_data = &out;
    init.write_fn = &write_to_string;
    init.error_handler_fn = &quiet;
    exr_context_t ctxt = nullptr;
    EXR_CHECK(exr_start_write(&ctxt, "test", EXR_WRITE_FILE_DIRECTLY, &init));
    int part = -1;
    EXR_CHECK(exr_add_part(ctxt, nullptr, file.storage, &part));
    exr_attr_v2f_t centre{};
    EXR_CHECK(exr_initialize_required_attr(ctxt, part, &file.data_window, &file.data_window, 1.0f,
                                           &centre, 1.0f, file.line_order, file.compression));
    for (const TestChannel& c : file.channels) {
        EXR_CHECK(exr_add_channel(ctxt, part, c.name.c_str(), c.type, EXR_PERCEPTUALLY_LOGARITHMIC,
                                  c.x_sampling, c.y_sampling));
    }
    if (file.storage == EXR_STORAGE_TILED) {
        EXR_CHECK(exr_set_tile_descriptor(ctxt, part, file.tile_w, file.tile_h, EXR_TILE_ONE_LEVEL,
                                          EXR_TILE_ROUND_DOWN));
    }
    EXR_CHECK(exr_write_header(ctxt));

    const exr_attr_box2i_t& dw = file.data_window;
    exr_encode_pipeline_t encode{};
    bool first = true;
    if (file.storage == EXR_STORAGE_SCANLINE) {
        int32_t lines = 0;
        EXR_CHECK(exr_get_scanlines_per_chunk(ctxt, part, &lines));
        // In increasing y whatever the line order: OpenEXRCore 3.1.5 writes chunks in no other.
        for (int y = dw.min.y; y <= dw.max.y; y += lines) {
            exr_chunk_info_t cinfo{};
            EXR_CHECK(exr_write_scanline_chunk_info(ctxt, part, y, &cinfo));
            write_chunk(ctxt, file, cinfo, dw.min.x, cinfo.start_y, encode, first);
            if (::testing::Test::HasFatalFailure()) return;
            first = false;
        }
    } else {
        const int w = dw.max.x - dw.min.x + 1, h = dw.max.y - dw.min.y + 1;
        for (int ty = 0; ty * file.tile_h < h; ++ty) {
            for (int tx = 0; tx * file.tile_w < w; ++tx) {
                exr_chunk_info_t cinfo{};
                EXR_CHECK(exr_write_tile_chunk_info(ctxt, part, tx, ty, 0, 0, &cinfo));
                write_chunk(ctxt, file, cinfo, dw.min.x + tx * file.tile_w,
                            dw.min.y + ty * file.tile_h, encode, first);
                if (::testing::Test::HasFatalFailure()) return;
                first = false;
            }
        }
    }
    EXR_CHECK(exr_encoding_destroy(ctxt, &encode));
    EXR_CHECK(exr_finish(&ctxt));
}

/// The bytes of `file`, written with OpenEXRCore.
std::string make_file(const TestFile& file) {
    std::string out;
    write_file(file, out);
    return out;
}

// Values exact in half (multiples of 1/8 below 2048), different in every channel and pixel.
float half_value(int x, int y, int c) { return float((x * 7 + y * 13 + c * 29) % 400 - 150) / 8; }
float float_value(int x, int y, int c) { return half_value(x, y, c) + 1e-4f * float(x - y + c); }

TestChannel channel(const std::string& name, exr_pixel_type_t type, int c) {
    if (type == EXR_PIXEL_HALF)
        return {name, type, [c](int x, int y) { return half_value(x, y, c); }};
    if (type == EXR_PIXEL_UINT) {
        return {name, type,
                [c](int x, int y) { return float((x * 31 + y * 17 + c + 9000) % 5000); }};
    }
    return {name, type, [c](int x, int y) { return float_value(x, y, c); }};
}

std::vector<TestChannel> rgb(exr_pixel_type_t type, const std::string& prefix = "") {
    return {channel(prefix + "R", type, 0), channel(prefix + "G", type, 1),
            channel(prefix + "B", type, 2)};
}

/// Checks that `img` holds `file`'s data window, channel by channel (nullptr: expects 0), bit
/// for bit.
void expect_pixels(const Image& img, const TestFile& file, const TestChannel* r,
                   const TestChannel* g, const TestChannel* b) {
    const exr_attr_box2i_t& dw = file.data_window;
    ASSERT_EQ(img.width, dw.max.x - dw.min.x + 1);
    ASSERT_EQ(img.height, dw.max.y - dw.min.y + 1);
    const TestChannel* chans[3] = {r, g, b};
    int wrong = 0;
    for (int y = dw.min.y; y <= dw.max.y; ++y) {
        for (int x = dw.min.x; x <= dw.max.x; ++x) {
            const Rgb& p = img.at(x - dw.min.x, y - dw.min.y);
            for (int c = 0; c < 3; ++c) {
                const float got = p[c], want = chans[c] ? chans[c]->value(x, y) : 0.0f;
                if (std::memcmp(&got, &want, 4) != 0 && ++wrong <= 5) {
                    ADD_FAILURE() << "pixel (" << x << ", " << y << ") channel " << c << ": " << got
                                  << ", expected " << want;
                }
            }
        }
    }
    EXPECT_EQ(wrong, 0);
}

std::string error_of(std::string_view bytes, const std::string& layer = "") {
    try {
        decode_exr_layer(bytes, layer);
    } catch (const ImageError& e) {
        return e.what();
    }
    return "(no error)";
}

// ---- Reading what other writers write ------------------------------------------------------

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
    const std::string key("dataWindow\0box2i\0", 17);
    const size_t at = bytes.find(key);
    ASSERT_NE(at, std::string::npos);
    const int32_t max_x = 1000;  // (0 0) - (15 9) becomes (0 0) - (1000 9)
    std::memcpy(&bytes[at + key.size() + 4 + 8], &max_x, 4);
    EXPECT_EQ(error_of(bytes), "invalid OpenEXR: the chunk at (0, 0) holds 96 bytes for 6006");
}

// ---- What luz writes ---------------------------------------------------------------------

/// Every float bit pattern class: NaNs with payloads, infinities, ±0, subnormals, extremes.
Image awkward_image(int w, int h, uint32_t seed) {
    Image img(w, h);
    std::mt19937 rng(seed);
    const uint32_t specials[] = {0x00000000u, 0x80000000u, 0x7f800000u, 0xff800000u,
                                 0x7fc00000u, 0x7fa12345u, 0xffc00001u, 0x00000001u,
                                 0x807fffffu, 0x7f7fffffu, 0xff7fffffu, 0x3f800000u};
    size_t i = 0;
    for (Rgb& p : img.pixels) {
        for (int c = 0; c < 3; ++c) {
            const uint32_t bits = (i % 5 == 0) ? specials[(i / 5) % 12] : uint32_t(rng());
            std::memcpy(&p[c], &bits, 4);
            ++i;
        }
    }
    return img;
}

bool same_bits(const Image& a, const Image& b) {
    return a.width == b.width && a.height == b.height &&
           std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(Rgb)) == 0;
}

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

// ---- Damaged files -----------------------------------------------------------------------

/// Decoding `bytes` either works or throws ImageError "invalid OpenEXR: ..." (or the codec's
/// own messages).
void expect_clean_failure_or_image(std::string_view bytes, const std::string& what) {
    std::string error;
    try {
        const Image img = decode_exr(bytes);
        EXPECT_GT(img.width, 0) << what;
    } catch (const ImageError& e) {
        error = e.what();
    } catch (const std::bad_alloc&) {  // a data window too large for memory
    }
    if (!error.empty()) {
        EXPECT_TRUE(error.rfind("invalid OpenEXR: ", 0) == 0 || error == "bad data window" ||
                    error == "not an OpenEXR file" || error.rfind("no R, G, B", 0) == 0)
            << what << ": " << error;
    }
}

TEST(ExrCodec, TruncatedFilesFailCleanly) {
    TestFile tiled;
    tiled.storage = EXR_STORAGE_TILED;
    tiled.tile_w = tiled.tile_h = 8;
    tiled.channels = rgb(EXR_PIXEL_HALF);
    const std::string files[] = {encode_exr(awkward_image(9, 40, 4)), make_file(tiled)};
    ASSERT_FALSE(HasFatalFailure());
    for (const std::string& bytes : files) {
        ::testing::internal::CaptureStderr();
        for (size_t keep = 0; keep < bytes.size(); ++keep) {
            const std::string error = error_of(bytes.substr(0, keep));
            if (keep < 4) {
                EXPECT_EQ(error, "not an OpenEXR file") << keep;
            } else {
                EXPECT_EQ(error.rfind("invalid OpenEXR: ", 0), 0u) << keep << ": " << error;
            }
        }
        EXPECT_EQ(::testing::internal::GetCapturedStderr(), "") << "the library printed";
    }
    // A message worth reading: the last chunk is cut short.
    const std::string bytes = encode_exr(Image(8, 8, Rgb{0.5f}));
    EXPECT_NE(error_of(bytes.substr(0, bytes.size() - 1)).find("chunk"), std::string::npos)
        << error_of(bytes.substr(0, bytes.size() - 1));
}

TEST(ExrCodec, CorruptFilesFailCleanly) {
    // Every byte of small files of each compression set to a few values: an image or an
    // ImageError, never a crash.
    std::vector<std::string> files = {encode_exr(awkward_image(7, 18, 9))};
    for (exr_compression_t compression :
         {EXR_COMPRESSION_NONE, EXR_COMPRESSION_RLE, EXR_COMPRESSION_ZIPS, EXR_COMPRESSION_PIZ,
          EXR_COMPRESSION_PXR24, EXR_COMPRESSION_B44}) {
        for (exr_storage_t storage : {EXR_STORAGE_SCANLINE, EXR_STORAGE_TILED}) {
            TestFile file;
            file.storage = storage;
            file.compression = compression;
            file.tile_w = file.tile_h = 4;
            file.data_window = box(-1, 2, 6, 9);
            file.channels = rgb(EXR_PIXEL_HALF);
            files.push_back(make_file(file));
            ASSERT_FALSE(HasFatalFailure());
        }
    }
    for (const std::string& bytes : files) {
        ::testing::internal::CaptureStderr();
        for (size_t i = 4; i < bytes.size(); ++i) {
            for (unsigned char v : {0x00, 0x01, 0x7f, 0xff}) {
                std::string bad = bytes;
                if (static_cast<unsigned char>(bad[i]) == v) continue;
                bad[i] = static_cast<char>(v);
                expect_clean_failure_or_image(bad, "byte " + std::to_string(i));
            }
        }
        EXPECT_EQ(::testing::internal::GetCapturedStderr(), "") << "the library printed";
    }
}

}  // namespace
}  // namespace luz
