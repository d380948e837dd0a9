// Netpbm-family codecs: binary PPM (P6, 8-bit) and PFM (float, rows from the bottom up).

#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "image/image_codecs.h"
#include "image/image_io.h"
#include "scene/cancel.h"

namespace luz {
namespace {

/// Reads the whitespace-separated header tokens of a Netpbm file ('#' starts a comment).
class HeaderReader {
  public:
    explicit HeaderReader(std::string_view bytes) : bytes_(bytes) {}

    /// The next token; empty at the end of the data.
    std::string_view token() {
        for (;;) {
            while (pos_ < bytes_.size() && is_space(bytes_[pos_])) ++pos_;
            if (pos_ < bytes_.size() && bytes_[pos_] == '#') {
                while (pos_ < bytes_.size() && bytes_[pos_] != '\n' && bytes_[pos_] != '\r') ++pos_;
                continue;
            }
            break;
        }
        const size_t start = pos_;
        while (pos_ < bytes_.size() && !is_space(bytes_[pos_]) && bytes_[pos_] != '#') ++pos_;
        return bytes_.substr(start, pos_ - start);
    }

    /// A positive integer token no larger than `max`.
    long positive(const char* what, long max) {
        const std::string_view t = token();
        long v = 0;
        const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
        if (t.empty() || ec != std::errc() || end != t.data() + t.size() || v <= 0 || v > max) {
            throw ImageError("bad " + std::string(what) + " '" + std::string(t) + "' in header");
        }
        return v;
    }

    /// The raster after the single whitespace character that ends the header.
    std::string_view raster() {
        if (pos_ >= bytes_.size() || !is_space(bytes_[pos_])) throw ImageError("file is truncated");
        // A CR LF pair counts as one line end (files written on Windows).
        if (bytes_[pos_] == '\r' && pos_ + 1 < bytes_.size() && bytes_[pos_ + 1] == '\n') ++pos_;
        return bytes_.substr(pos_ + 1);
    }

  private:
    static bool is_space(char c) {
        return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
    }

    std::string_view bytes_;
    size_t pos_ = 0;
};

/// Largest width or height accepted: an Image indexes with int.
constexpr long max_side = std::numeric_limits<int>::max();

/// Checks that `raster` holds w·h·per_pixel bytes (without overflow).
void require_raster(std::string_view raster, long w, long h, size_t per_pixel) {
    const size_t pixels = static_cast<size_t>(w) * static_cast<size_t>(h);
    if (pixels / static_cast<size_t>(h) != static_cast<size_t>(w) ||
        pixels > raster.size() / per_pixel) {
        throw ImageError("file is truncated");
    }
}

/// Appends a float32 in little-endian byte order.
void put_float_le(std::string& out, float v) {
    const uint32_t u = std::bit_cast<uint32_t>(v);
    const char b[4] = {static_cast<char>(u & 0xff), static_cast<char>((u >> 8) & 0xff),
                       static_cast<char>((u >> 16) & 0xff), static_cast<char>((u >> 24) & 0xff)};
    out.append(b, 4);
}

/// A float32 from 4 bytes in the given byte order.
float get_float(const char* p, bool little_endian) {
    const auto b = [p](int i) { return static_cast<uint32_t>(static_cast<unsigned char>(p[i])); };
    const uint32_t u = little_endian ? b(0) | b(1) << 8 | b(2) << 16 | b(3) << 24
                                     : b(3) | b(2) << 8 | b(1) << 16 | b(0) << 24;
    return std::bit_cast<float>(u);
}

}  // namespace

std::string encode_ppm(const Image& img, Encoding e) {
    std::string out =
        "P6\n" + std::to_string(img.width) + " " + std::to_string(img.height) + "\n255\n";
    const size_t header = out.size();
    out.resize(header + img.pixels.size() * 3);
    char* p = out.data() + header;
    for (int y = 0; y < img.height; ++y) {
        check_cancel();  // row by row: an 8192² image takes a second
        for (int x = 0; x < img.width; ++x) {
            const Rgb& c = img.at(x, y);
            *p++ = static_cast<char>(encode_8bit(c.x, e));
            *p++ = static_cast<char>(encode_8bit(c.y, e));
            *p++ = static_cast<char>(encode_8bit(c.z, e));
        }
    }
    return out;
}

Image decode_ppm(std::string_view bytes) {
    HeaderReader header(bytes);
    const std::string_view magic = header.token();
    if (magic != "P6") {
        if (magic.size() == 2 && magic[0] == 'P') {
            throw ImageError("unsupported Netpbm variant '" + std::string(magic) +
                             "' (only binary PPM, P6)");
        }
        throw ImageError("not a PPM file");
    }
    const long w = header.positive("width", max_side);
    const long h = header.positive("height", max_side);
    const long maxval = header.positive("maxval", 65535);
    const std::string_view raster = header.raster();
    const size_t bytes_per_sample = maxval < 256 ? 1 : 2;
    require_raster(raster, w, h, 3 * bytes_per_sample);

    // Samples become v / maxval (2-byte samples are big-endian).
    Image img(static_cast<int>(w), static_cast<int>(h));
    const auto* s = reinterpret_cast<const unsigned char*>(raster.data());
    const float m = static_cast<float>(maxval);
    const auto sample = [&](size_t i) {
        const unsigned v = bytes_per_sample == 1 ? s[i] : (unsigned{s[2 * i]} << 8) | s[2 * i + 1];
        return static_cast<float>(v) / m;
    };
    for (size_t i = 0; i < img.pixels.size(); ++i) {
        img.pixels[i] = Rgb{sample(3 * i), sample(3 * i + 1), sample(3 * i + 2)};
    }
    return img;
}

std::string encode_pfm(const Image& img) {
    std::string out =
        "PF\n" + std::to_string(img.width) + " " + std::to_string(img.height) + "\n-1.0\n";
    out.reserve(out.size() + img.pixels.size() * 12);
    for (int y = img.height - 1; y >= 0; --y) {  // rows from the bottom up
        check_cancel();                          // row by row: an 8192² image takes seconds
        for (int x = 0; x < img.width; ++x) {
            const Rgb& c = img.at(x, y);
            put_float_le(out, c.x);
            put_float_le(out, c.y);
            put_float_le(out, c.z);
        }
    }
    return out;
}

Image decode_pfm(std::string_view bytes) {
    HeaderReader header(bytes);
    const std::string_view magic = header.token();
    if (magic != "PF" && magic != "Pf") throw ImageError("not a PFM file");
    const int channels = magic == "PF" ? 3 : 1;
    const long w = header.positive("width", max_side);
    const long h = header.positive("height", max_side);
    // The scale's sign gives the byte order (negative: little-endian); its size means nothing.
    const std::string_view t = header.token();
    double scale = 0;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), scale);
    if (t.empty() || ec != std::errc() || end != t.data() + t.size() || scale == 0 ||
        !std::isfinite(scale)) {
        throw ImageError("bad scale '" + std::string(t) + "' in header");
    }
    const bool little_endian = scale < 0;
    const std::string_view raster = header.raster();
    require_raster(raster, w, h, 4 * static_cast<size_t>(channels));

    Image img(static_cast<int>(w), static_cast<int>(h));
    const char* p = raster.data();
    for (int y = img.height - 1; y >= 0; --y) {  // rows from the bottom up
        for (int x = 0; x < img.width; ++x) {
            if (channels == 3) {
                img.at(x, y) = Rgb{get_float(p, little_endian), get_float(p + 4, little_endian),
                                   get_float(p + 8, little_endian)};
                p += 12;
            } else {
                img.at(x, y) = Rgb{get_float(p, little_endian)};
                p += 4;
            }
        }
    }
    return img;
}

}  // namespace luz
