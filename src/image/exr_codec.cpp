// OpenEXR codec on OpenEXRCore, the library's C API: luz links libOpenEXRCore alone, not the C++
// stack (libOpenEXR, Iex, IlmThread, Imath) whose loading cost every luz process ~2 ms of start.
// Writes 32-bit float R, G, B (exact, unclamped, ZIP); reads R, G, B or Y of any scanline or
// tiled file. Both go through memory (the context's read, size and write functions), and the
// library's messages become the exceptions' text instead of lines on stderr.

#include <openexr.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "image/image_codecs.h"
#include "image/image_io.h"
#include "scene/cancel.h"

namespace luz {
namespace {

static_assert(sizeof(Rgb) == 3 * sizeof(float), "Rgb must be three packed floats");

constexpr int32_t kPixelStride = static_cast<int32_t>(sizeof(Rgb));

/// A context's user data: the bytes it reads or writes, and the first message it reported.
struct Stream {
    std::string_view in;
    std::string out;
    std::string error;
};

Stream* stream_of(exr_const_context_t ctxt) {
    void* data = nullptr;
    if (ctxt == nullptr || exr_get_user_data(ctxt, &data) != EXR_ERR_SUCCESS) return nullptr;
    return static_cast<Stream*>(data);
}

/// The library's error handler: keeps the first (most specific) message instead of printing it.
void record_error(exr_const_context_t ctxt, exr_result_t code, const char* msg) noexcept {
    Stream* s = stream_of(ctxt);
    if (s == nullptr || !s->error.empty()) return;
    try {
        s->error = msg != nullptr ? msg : exr_get_default_error_message(code);
    } catch (...) {  // out of memory: the code's own message will do
    }
}

int64_t read_memory(exr_const_context_t, void* user, void* buffer, uint64_t size, uint64_t offset,
                    exr_stream_error_func_ptr_t) noexcept {
    const std::string_view in = static_cast<Stream*>(user)->in;
    if (offset >= in.size()) return 0;
    const size_t n = static_cast<size_t>(std::min<uint64_t>(size, in.size() - offset));
    std::memcpy(buffer, in.data() + offset, n);
    return static_cast<int64_t>(n);
}

int64_t size_of_memory(exr_const_context_t, void* user) noexcept {
    return static_cast<int64_t>(static_cast<Stream*>(user)->in.size());
}

/// Writes at `offset` (the library comes back to fill in the chunk offset table).
int64_t write_memory(exr_const_context_t, void* user, const void* buffer, uint64_t size,
                     uint64_t offset, exr_stream_error_func_ptr_t) noexcept {
    std::string& out = static_cast<Stream*>(user)->out;
    constexpr uint64_t max = std::numeric_limits<int64_t>::max();
    if (size > max || offset > max - size) return -1;
    try {
        if (offset + size > out.size()) out.resize(static_cast<size_t>(offset + size));
    } catch (...) {
        return -1;
    }
    if (size > 0) std::memcpy(out.data() + offset, buffer, static_cast<size_t>(size));
    return static_cast<int64_t>(size);
}

exr_context_initializer_t initializer(Stream& s) {
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = &record_error;
    init.user_data = &s;
    return init;
}

/// The library's message for a failed call: the one it reported, else the code's.
std::string message(const Stream& s, exr_result_t rv) {
    return s.error.empty() ? std::string(exr_get_default_error_message(rv)) : s.error;
}

/// A context and its coding pipelines, released in order whatever happens.
struct Session {
    exr_context_t ctxt = nullptr;
    exr_encode_pipeline_t encode{};
    exr_decode_pipeline_t decode{};
    bool encoding = false, decoding = false;

    Session() = default;
    Session(const Session&) = delete;
    Session& operator=(const Session&) = delete;
    ~Session() {
        if (encoding) exr_encoding_destroy(ctxt, &encode);
        if (decoding) exr_decoding_destroy(ctxt, &decode);
        if (ctxt != nullptr) exr_finish(&ctxt);
    }
};

// A chunk that compressing does not shrink is stored raw. OpenEXRCore 3.1.5 keeps a ZIP chunk
// that compresses to exactly its raw size as compressed, but every reader (the library
// included) takes a chunk of that size for a raw one; later versions store it raw.
using Compress = exr_result_t (*)(exr_encode_pipeline_t*);

/// The pipeline's compress function: the library's (in encoding_user_data), then the check.
exr_result_t compress_or_store(exr_encode_pipeline_t* encode) {
    const exr_result_t rv = (*static_cast<const Compress*>(encode->encoding_user_data))(encode);
    if (rv == EXR_ERR_SUCCESS && encode->compressed_bytes >= encode->packed_bytes &&
        encode->compressed_buffer != encode->packed_buffer) {
        std::memcpy(encode->compressed_buffer, encode->packed_buffer, encode->packed_bytes);
        encode->compressed_bytes = encode->packed_bytes;
    }
    return rv;
}

/// How many times its packed size a chunk of `compression` can at most unpack to, or 0 where
/// no bound is known (DWAA, DWAB). RLE stores a run of at most 128 bytes in two; zlib (ZIP,
/// ZIPS) inflates at most 1032 times; PXR24 is zlib over floats cut to three bytes; PIZ's
/// Huffman code spends at least 10 bits on a run of at most 256 16-bit values (410 times); B44
/// packs a 4 × 4 block of half values (32 bytes) into 14, B44A a flat one into 3.
uint64_t max_expansion(exr_compression_t compression) {
    switch (compression) {
        case EXR_COMPRESSION_NONE:
            return 1;
        case EXR_COMPRESSION_RLE:
            return 64;
        case EXR_COMPRESSION_ZIPS:
        case EXR_COMPRESSION_ZIP:
            return 1032;
        case EXR_COMPRESSION_PXR24:
            return 1032 * 4 / 3 + 1;
        case EXR_COMPRESSION_PIZ:
            return 512;
        case EXR_COMPRESSION_B44:
        case EXR_COMPRESSION_B44A:
            return 11;
        default:
            return 0;
    }
}

}  // namespace

std::string encode_exr(const Image& img) { return encode_exr_layers(img, {}); }

std::string encode_exr_layers(const Image& img, const std::vector<ExrLayer>& layers) {
    // Channel name → its first float (component c of the first pixel of its image); a name given
    // twice takes the later image.
    std::vector<std::pair<std::string, const float*>> channels;
    auto add = [&](std::string name, const Image& image, int c) {
        const float* first = reinterpret_cast<const float*>(image.pixels.data()) + c;
        for (auto& channel : channels) {
            if (channel.first == name) {
                channel.second = first;
                return;
            }
        }
        channels.emplace_back(std::move(name), first);
    };
    add("R", img, 0);
    add("G", img, 1);
    add("B", img, 2);
    for (const ExrLayer& layer : layers) {
        if (layer.image->width != img.width || layer.image->height != img.height) {
            throw ImageError("EXR layer " + layer.name + " is not the image's size");
        }
        if (layer.scalar) {
            add(layer.name + ".Y", *layer.image, 0);
        } else {
            add(layer.name + ".R", *layer.image, 0);
            add(layer.name + ".G", *layer.image, 1);
            add(layer.name + ".B", *layer.image, 2);
        }
    }

    Stream out;
    const auto check = [&out](exr_result_t rv) {
        if (rv != EXR_ERR_SUCCESS) throw ImageError("EXR encoding failed: " + message(out, rv));
    };
    if (img.width > std::numeric_limits<int32_t>::max() / kPixelStride) {
        throw ImageError("EXR encoding failed: the image is too wide");
    }
    const int32_t line_stride = kPixelStride * img.width;

    exr_context_initializer_t init = initializer(out);
    init.write_fn = &write_memory;
    Session session;
    exr_context_t& ctxt = session.ctxt;
    check(exr_start_write(&ctxt, "memory", EXR_WRITE_FILE_DIRECTLY, &init));
    int part = 0;
    check(exr_add_part(ctxt, nullptr, EXR_STORAGE_SCANLINE, &part));
    // Data and display windows 0..w-1 × 0..h-1, increasing y, ZIP (16 lines a chunk).
    check(exr_initialize_required_attr_simple(ctxt, part, img.width, img.height,
                                              EXR_COMPRESSION_ZIP));
    for (const auto& channel : channels) {
        if (channel.first.size() > 31) check(exr_set_longname_support(ctxt, 1));
    }
    for (const auto& channel : channels) {
        check(exr_add_channel(ctxt, part, channel.first.c_str(), EXR_PIXEL_FLOAT,
                              EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1));
    }
    check(exr_write_header(ctxt));

    int32_t lines = 0;
    check(exr_get_scanlines_per_chunk(ctxt, part, &lines));
    if (lines <= 0) check(EXR_ERR_INVALID_ATTR);
    exr_encode_pipeline_t& encode = session.encode;
    Compress library_compress = nullptr;
    for (int64_t y = 0; y < img.height; y += lines) {
        check_cancel();  // chunk by chunk (16 lines): an 8192² image takes seconds
        exr_chunk_info_t cinfo{};
        check(exr_write_scanline_chunk_info(ctxt, part, static_cast<int>(y), &cinfo));
        if (!session.encoding) {
            check(exr_encoding_initialize(ctxt, part, &cinfo, &encode));
            session.encoding = true;
        } else {
            check(exr_encoding_update(ctxt, part, &cinfo, &encode));
        }
        // The library's channels are sorted by name: find each one's pixels.
        for (int c = 0; c < encode.channel_count; ++c) {
            exr_coding_channel_info_t& ch = encode.channels[c];
            const auto it = std::find_if(
                channels.begin(), channels.end(),
                [&ch](const auto& channel) { return channel.first == ch.channel_name; });
            if (it == channels.end()) check(EXR_ERR_NO_ATTR_BY_NAME);
            const float* first = it->second + static_cast<size_t>(cinfo.start_y) * img.width * 3;
            ch.encode_from_ptr = reinterpret_cast<const uint8_t*>(first);
            ch.user_pixel_stride = kPixelStride;
            ch.user_line_stride = line_stride;
            ch.user_bytes_per_element = sizeof(float);
            ch.user_data_type = EXR_PIXEL_FLOAT;
        }
        if (y == 0) {
            check(exr_encoding_choose_default_routines(ctxt, part, &encode));
            if (encode.compress_fn != nullptr) {
                library_compress = encode.compress_fn;
                encode.encoding_user_data = &library_compress;
                encode.compress_fn = &compress_or_store;
            }
        }
        check(exr_encoding_run(ctxt, part, &encode));
    }
    check(exr_encoding_destroy(ctxt, &encode));
    session.encoding = false;
    check(exr_finish(&ctxt));  // writes the chunk offset table
    return std::move(out.out);
}

Image decode_exr(std::string_view bytes) { return decode_exr_layer(bytes, ""); }

Image decode_exr_layer(std::string_view bytes, const std::string& layer) {
    if (bytes.size() < 4 || std::memcmp(bytes.data(), "\x76\x2f\x31\x01", 4) != 0) {
        throw ImageError("not an OpenEXR file");
    }
    Stream in;
    in.in = bytes;
    // A message of a call that succeeded was a warning (the header parser reports what it
    // skips): only a failed call's own messages name the failure.
    const auto check = [&in](exr_result_t rv) {
        if (rv != EXR_ERR_SUCCESS) throw ImageError("invalid OpenEXR: " + message(in, rv));
        in.error.clear();
    };
    const auto fail = [](const std::string& what) { throw ImageError("invalid OpenEXR: " + what); };

    exr_context_initializer_t init = initializer(in);
    init.read_fn = &read_memory;
    init.size_fn = &size_of_memory;
    Session session;
    exr_context_t& ctxt = session.ctxt;
    check(exr_start_read(&ctxt, "memory", &init));  // reads and checks the header
    constexpr int part = 0;                         // the first part of a multi-part file
    exr_storage_t storage{};
    check(exr_get_storage(ctxt, part, &storage));
    if (storage != EXR_STORAGE_SCANLINE && storage != EXR_STORAGE_TILED) {
        fail("deep data is not supported");
    }

    exr_attr_box2i_t dw{};
    check(exr_get_data_window(ctxt, part, &dw));
    const int64_t w = int64_t{dw.max.x} - dw.min.x + 1;
    const int64_t h = int64_t{dw.max.y} - dw.min.y + 1;
    if (w <= 0 || h <= 0 || w > std::numeric_limits<int>::max() ||
        h > std::numeric_limits<int>::max()) {
        throw ImageError("bad data window");
    }
    if (w > std::numeric_limits<int32_t>::max() / kPixelStride) fail("the image is too wide");

    // Channels absent from the file read as 0; a luminance-only file fills all three.
    const exr_attr_chlist_t* list = nullptr;
    check(exr_get_channels(ctxt, part, &list));
    if (list == nullptr) check(EXR_ERR_MISSING_REQ_ATTR);
    const std::string prefix = layer.empty() ? "" : layer + ".";
    const std::string R = prefix + "R", G = prefix + "G", B = prefix + "B", Y = prefix + "Y";
    const auto find = [list](const std::string& name) -> const exr_attr_chlist_entry_t* {
        for (int i = 0; i < list->num_channels; ++i) {
            if (list->entries[i].name.str != nullptr && name == list->entries[i].name.str) {
                return &list->entries[i];
            }
        }
        return nullptr;
    };
    const bool has_rgb = find(R) != nullptr || find(G) != nullptr || find(B) != nullptr;
    const bool has_y = find(Y) != nullptr;
    if (!has_rgb && !has_y)
        throw ImageError("no " + R + ", " + G + ", " + B + " or " + Y + " channel");
    const std::string* names[3] = {&R, &G, &B};
    if (!has_rgb) names[0] = &Y;
    const int count = has_rgb ? 3 : 1;
    for (int c = 0; c < count; ++c) {
        const exr_attr_chlist_entry_t* e = find(*names[c]);
        if (e != nullptr && (e->x_sampling != 1 || e->y_sampling != 1)) {
            fail("channel " + *names[c] + " is subsampled (" + std::to_string(e->x_sampling) + "x" +
                 std::to_string(e->y_sampling) + "), which luz does not read");
        }
    }

    int32_t lines = 1;  // per chunk, for scanline files
    int64_t tile_w = w, tile_h = h;
    if (storage == EXR_STORAGE_SCANLINE) {
        check(exr_get_scanlines_per_chunk(ctxt, part, &lines));
        if (lines <= 0) fail("bad number of lines per chunk");
        // The library counts a subsampled channel's lines in a chunk as lines / y_sampling: it
        // overruns its buffers unless that is exact.
        for (int i = 0; i < list->num_channels; ++i) {
            const int32_t ys = list->entries[i].y_sampling;
            if (ys > 1 && lines > 1 && lines % ys != 0) {
                fail("channel " + std::string(list->entries[i].name.str) + ": y subsampling " +
                     std::to_string(ys) + " does not divide the " + std::to_string(lines) +
                     " lines of a chunk");
            }
        }
    } else {
        uint32_t tx = 0, ty = 0;
        exr_tile_level_mode_t levels{};
        exr_tile_round_mode_t round{};
        check(exr_get_tile_descriptor(ctxt, part, &tx, &ty, &levels, &round));
        int32_t level_w = 0, level_h = 0;  // level 0 (full resolution) of a mipmap or ripmap
        check(exr_get_level_sizes(ctxt, part, 0, 0, &level_w, &level_h));
        if (tx == 0 || ty == 0 || level_w != w || level_h != h) fail("bad tile description");
        tile_w = std::min<int64_t>(tx, w);
        tile_h = std::min<int64_t>(ty, h);
    }

    // Taken when the first chunk has passed its checks (the library has then read and checked
    // the chunk table): a corrupt data window is refused before it costs memory. Unwritten:
    // every chunk's pixels are written once it has decoded, those of absent channels with 0.
    Image img;
    bool present[3] = {};
    for (int c = 0; c < count; ++c) present[c] = find(*names[c]) != nullptr;
    // Channels luz does not read are decoded into `scratch`, every line over the last: with a
    // pointer for every channel, the library keeps to its general routines (its fast ones for
    // three half channels assume that all three are being read). Unwritten, like the image.
    std::unique_ptr<float[]> scratch;
    std::unique_ptr<float[]> line;  // see `sparse` below
    exr_decode_pipeline_t& decode = session.decode;
    // Decodes chunk `cinfo`, columns x0.. and rows y0.. of the image, in place. Each chunk is
    // checked to have the size its place gives it: together they cover the image.
    const auto decode_chunk = [&](const exr_chunk_info_t& cinfo, int64_t x0, int64_t y0,
                                  int64_t chunk_h) {
        if (cinfo.width != std::min(tile_w, w - x0) || cinfo.height != std::min(chunk_h, h - y0)) {
            fail("bad chunk size " + std::to_string(cinfo.width) + "x" +
                 std::to_string(cinfo.height) + " at (" + std::to_string(x0) + ", " +
                 std::to_string(y0) + ")");
        }
        // A chunk is never bigger than its pixels; OpenEXRCore 3.1.5 does not check that an
        // uncompressed one is exactly their size (and would then read memory it never filled).
        if (cinfo.packed_size > cinfo.unpacked_size || (cinfo.compression == EXR_COMPRESSION_NONE &&
                                                        cinfo.packed_size != cinfo.unpacked_size)) {
            fail("the chunk at (" + std::to_string(x0) + ", " + std::to_string(y0) + ") holds " +
                 std::to_string(cinfo.packed_size) + " bytes for " +
                 std::to_string(cinfo.unpacked_size));
        }
        // Nor does it unpack to more than its compression can give (a corrupt data window of a
        // small file would have the library take gigabytes for the chunk before failing). The
        // margin leaves tiny chunks alone, whatever their codec's fixed overhead.
        constexpr uint64_t kMargin = 4096;
        const uint64_t expansion = max_expansion(static_cast<exr_compression_t>(cinfo.compression));
        if (expansion != 0 && cinfo.unpacked_size > expansion * cinfo.packed_size + kMargin) {
            fail("the chunk at (" + std::to_string(x0) + ", " + std::to_string(y0) + ") holds " +
                 std::to_string(cinfo.packed_size) + " bytes, too few for its " +
                 std::to_string(cinfo.unpacked_size));
        }
        if (!session.decoding) {
            check(exr_decoding_initialize(ctxt, part, &cinfo, &decode));
            session.decoding = true;
        } else {
            check(exr_decoding_update(ctxt, part, &cinfo, &decode));
        }
        if (!scratch) {
            img = Image(static_cast<int>(w), static_cast<int>(h), Unwritten{});
            scratch.reset(new float[static_cast<size_t>(tile_w)]);
        }
        Rgb* const corner = img.pixels.data() + y0 * w + x0;
        char* first = reinterpret_cast<char*>(corner);
        // A line where a subsampled channel has no samples (one line a chunk): OpenEXRCore
        // 3.1.5 leaves that channel out when it picks its unpacking routine, not when it runs
        // it, so that a half Y read alone into the image (12 bytes a pixel, the layout of three
        // interleaved floats) would be unpacked as three channels. Such a line is read into
        // `line` instead (8 bytes a pixel, a layout no fast routine takes), then copied.
        bool sparse = false;
        for (int c = 0; c < decode.channel_count; ++c) {
            sparse = sparse || decode.channels[c].height == 0;
        }
        if (sparse && cinfo.height != 1) fail("bad subsampling");
        if (sparse && !line) line.reset(new float[static_cast<size_t>(2 * count * w)]);
        for (int c = 0; c < decode.channel_count; ++c) {
            exr_coding_channel_info_t& ch = decode.channels[c];
            int slot = -1;
            for (int k = 0; k < count; ++k) {
                if (*names[k] == ch.channel_name) slot = k;
            }
            if (slot >= 0 && sparse) {
                ch.decode_to_ptr = reinterpret_cast<uint8_t*>(line.get() + 2 * slot * w);
                ch.user_pixel_stride = 2 * sizeof(float);
                ch.user_line_stride = 0;  // a chunk of one line
            } else if (slot >= 0) {
                ch.decode_to_ptr = reinterpret_cast<uint8_t*>(first + slot * sizeof(float));
                ch.user_pixel_stride = kPixelStride;
                ch.user_line_stride = static_cast<int32_t>(kPixelStride * w);
            } else {
                ch.decode_to_ptr = reinterpret_cast<uint8_t*>(scratch.get());
                ch.user_pixel_stride = sizeof(float);
                ch.user_line_stride = 0;
            }
            ch.user_bytes_per_element = sizeof(float);
            ch.user_data_type = EXR_PIXEL_FLOAT;  // HALF, FLOAT and UINT all read as float
        }
        check(exr_decoding_choose_default_routines(ctxt, part, &decode));
        // A chunk as big as its pixels is stored raw, whatever the compression (writers store
        // a chunk raw when compressing does not shrink it); OpenEXRCore 3.1.5 would still run
        // its B44 decoder on one, scrambling, say, the float channels of a B44 file.
        if (cinfo.packed_size == cinfo.unpacked_size) decode.decompress_fn = nullptr;
        check(exr_decoding_run(ctxt, part, &decode));
        if (sparse) {
            for (int k = 0; k < count; ++k) {
                if (!present[k]) continue;
                for (int64_t x = 0; x < cinfo.width; ++x) corner[x][k] = line[2 * (k * w + x)];
            }
        }
        for (int k = 0; k < count; ++k) {
            if (present[k]) continue;
            for (int64_t y = 0; y < cinfo.height; ++y) {
                for (int64_t x = 0; x < cinfo.width; ++x) corner[y * w + x][k] = 0.0f;
            }
        }
    };

    if (storage == EXR_STORAGE_SCANLINE) {
        for (int64_t y = dw.min.y; y <= dw.max.y; y += lines) {
            exr_chunk_info_t cinfo{};
            check(exr_read_scanline_chunk_info(ctxt, part, static_cast<int>(y), &cinfo));
            if (cinfo.start_y != y || cinfo.start_x != dw.min.x) {
                fail("bad chunk at line " + std::to_string(y));
            }
            decode_chunk(cinfo, 0, y - dw.min.y, lines);
        }
    } else {
        for (int64_t ty = 0; ty * tile_h < h; ++ty) {
            for (int64_t tx = 0; tx * tile_w < w; ++tx) {
                exr_chunk_info_t cinfo{};
                check(exr_read_tile_chunk_info(ctxt, part, static_cast<int>(tx),
                                               static_cast<int>(ty), 0, 0, &cinfo));
                decode_chunk(cinfo, tx * tile_w, ty * tile_h, tile_h);
            }
        }
    }

    if (!has_rgb) {
        for (Rgb& p : img.pixels) p = Rgb{p.x};
    }
    return img;
}

}  // namespace luz
