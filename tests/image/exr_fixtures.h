// Shared helpers of the OpenEXR codec tests: test files written with OpenEXRCore (channels of
// every pixel type, tiles, data windows, compressions), checks of decoded pixels, error messages,
// and images of every float bit pattern class.
#pragma once

#include <OpenEXR/openexr.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <functional>
#include <random>
#include <string>
#include <string_view>
#include <vector>

#include "image/image_codecs.h"
#include "image/image_io.h"

namespace luz::test {

/// A channel of a test file: its value at pixel (x, y) of the data window (absolute
/// coordinates), exactly representable in its type.
struct TestChannel {
    std::string name;
    exr_pixel_type_t type = EXR_PIXEL_FLOAT;
    std::function<float(int, int)> value;
    int x_sampling = 1, y_sampling = 1;
};

inline exr_attr_box2i_t box(int x0, int y0, int x1, int y1) {
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

inline int64_t write_to_string(exr_const_context_t, void* user, const void* buffer, uint64_t size,
                               uint64_t offset, exr_stream_error_func_ptr_t) {
    std::string& out = *static_cast<std::string*>(user);
    if (offset + size > out.size()) out.resize(offset + size);
    std::memcpy(out.data() + offset, buffer, size);
    return static_cast<int64_t>(size);
}

inline void quiet(exr_const_context_t, exr_result_t, const char*) {}

#define EXR_CHECK(call) ASSERT_EQ((call), EXR_ERR_SUCCESS) << #call

using Compress = exr_result_t (*)(exr_encode_pipeline_t*);
inline Compress library_compress = nullptr;

/// A chunk that compressing does not shrink is stored raw, as OpenEXR's C++ library does:
/// OpenEXRCore 3.1.5 keeps one of exactly its raw size compressed, which readers take for raw
/// data, and B44 chunks larger than raw, which it then refuses to read.
inline exr_result_t compress_or_store(exr_encode_pipeline_t* encode) {
    const exr_result_t rv = library_compress(encode);
    if (rv == EXR_ERR_SUCCESS && encode->compressed_bytes >= encode->packed_bytes &&
        encode->compressed_buffer != encode->packed_buffer) {
        std::memcpy(encode->compressed_buffer, encode->packed_buffer, encode->packed_bytes);
        encode->compressed_bytes = encode->packed_bytes;
    }
    return rv;
}

/// Encodes one chunk (its pixels from x0, y0) of `file` through the library's pipeline.
inline void write_chunk(exr_context_t ctxt, const TestFile& file, const exr_chunk_info_t& cinfo,
                        int x0, int y0, exr_encode_pipeline_t& encode, bool first) {
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

inline void write_file(const TestFile& file, std::string& out) {
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
inline std::string make_file(const TestFile& file) {
    std::string out;
    write_file(file, out);
    return out;
}

// Values exact in half (multiples of 1/8 below 2048), different in every channel and pixel.
inline float half_value(int x, int y, int c) {
    return float((x * 7 + y * 13 + c * 29) % 400 - 150) / 8;
}
inline float float_value(int x, int y, int c) {
    return half_value(x, y, c) + 1e-4f * float(x - y + c);
}

inline TestChannel channel(const std::string& name, exr_pixel_type_t type, int c) {
    if (type == EXR_PIXEL_HALF)
        return {name, type, [c](int x, int y) { return half_value(x, y, c); }};
    if (type == EXR_PIXEL_UINT) {
        return {name, type,
                [c](int x, int y) { return float((x * 31 + y * 17 + c + 9000) % 5000); }};
    }
    return {name, type, [c](int x, int y) { return float_value(x, y, c); }};
}

inline std::vector<TestChannel> rgb(exr_pixel_type_t type, const std::string& prefix = "") {
    return {channel(prefix + "R", type, 0), channel(prefix + "G", type, 1),
            channel(prefix + "B", type, 2)};
}

/// Checks that `img` holds `file`'s data window, channel by channel (nullptr: expects 0), bit
/// for bit.
inline void expect_pixels(const Image& img, const TestFile& file, const TestChannel* r,
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

/// Overwrites one corner coordinate of a file's data window in its header: `field` 0..3 is x
/// min, y min, x max, y max (after the attribute's name, type and size). Fails the test when the
/// header has no data window.
inline void set_data_window(std::string& bytes, int field, int32_t value) {
    const std::string key("dataWindow\0box2i\0", 17);
    const size_t at = bytes.find(key);
    ASSERT_NE(at, std::string::npos);
    std::memcpy(&bytes[at + key.size() + 4 + 4 * field], &value, sizeof value);
}

inline std::string error_of(std::string_view bytes, const std::string& layer = "") {
    try {
        decode_exr_layer(bytes, layer);
    } catch (const ImageError& e) {
        return e.what();
    }
    return "(no error)";
}

/// Every float bit pattern class: NaNs with payloads, infinities, ±0, subnormals, extremes.
inline Image awkward_image(int w, int h, uint32_t seed) {
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

}  // namespace luz::test
