// A work item's pixels as checkpoint bytes (render/checkpoint.h): raw copies of plain values and
// of the output's pixels in a rectangle, read back in the same order; TileWriter and TileReader
// let one description of a tile's bytes serve both ways.
#pragma once

#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>

#include "image/image.h"
#include "render/aov.h"
#include "scene/input_error.h"

namespace luz {

/// Checkpoint bytes of a work item (render/checkpoint.h): raw copies of plain values and of
/// the output's pixels in a rectangle, read back in the same order.
template <class T>
void append_raw(std::string& out, const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    out.append(reinterpret_cast<const char*>(&v), sizeof v);
}
template <class T>
void read_raw(std::string_view& in, T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    if (in.size() < sizeof v)
        throw InputError("--checkpoint: damaged checkpoint (a tile is short)");
    std::memcpy(&v, in.data(), sizeof v);
    in.remove_prefix(sizeof v);
}
/// The pixels of `r` of an image, or of the image and each term plane of a TermOut.
void append_rect(std::string& out, const Image& img, const PixelRect& r);
void read_rect(std::string_view& in, Image& img, const PixelRect& r);
void append_rect(std::string& out, const TermOut& o, const PixelRect& r);
void read_rect(std::string_view& in, TermOut& o, const PixelRect& r);
void append_rect(std::string& out, const ImageRows& o, const PixelRect& r);
void read_rect(std::string_view& in, ImageRows& o, const PixelRect& r);

/// Writes a tile's bytes: raw(v) a plain value, rect(o, r) an output's pixels in r, plane(p,
/// row, r) the values of a row-major plane of `row` values a row in r.
struct TileWriter {
    std::string& bytes;

    template <class T>
    void raw(const T& v) {
        append_raw(bytes, v);
    }
    template <class Out>
    void rect(const Out& o, const PixelRect& r) {
        append_rect(bytes, o, r);
    }
    template <class T>
    void plane(const T* p, size_t row, const PixelRect& r) {
        static_assert(std::is_trivially_copyable_v<T>);
        for (int y = r.y0; y < r.y1; ++y)
            bytes.append(reinterpret_cast<const char*>(p + y * row + r.x0), sizeof(T) * r.width());
    }
};

/// Reads back what TileWriter wrote, consuming `in` (InputError when it is short).
struct TileReader {
    std::string_view& in;

    template <class T>
    void raw(T& v) {
        read_raw(in, v);
    }
    template <class Out>
    void rect(Out& o, const PixelRect& r) {
        read_rect(in, o, r);
    }
    template <class T>
    void plane(T* p, size_t row, const PixelRect& r) {
        for (int y = r.y0; y < r.y1; ++y)
            for (int x = r.x0; x < r.x1; ++x) read_raw(in, p[y * row + x]);
    }
};

}  // namespace luz
