// A work item's pixels as checkpoint bytes (render/checkpoint.h): raw copies of plain values and
// of the output's pixels in a rectangle, read back in the same order.
#pragma once

#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>

#include "image/image.h"
#include "render/aov.h"
#include "render/work_items.h"
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

}  // namespace luz
