// Image files: picks the format, encodes in memory, and writes atomically (temporary file in the
// same directory, then renamed); reads whole files and decodes them by their content.

#include "image/image_io.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <system_error>

#include "image/atomic_file.h"
#include "image/image_codecs.h"

namespace luz {
namespace {

constexpr const char* supported_extensions = ".png, .ppm, .pfm, .exr";

/// The whole content of a file; ImageError naming `path` if it cannot be read.
std::string read_file(const std::string& path) {
    const auto fail = [&path](int err) {
        throw ImageError(path + ": cannot read: " + error_text(err));
    };
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) fail(errno);
    std::string bytes;
    struct stat st {};
    if (::fstat(fd, &st) == 0 && st.st_size > 0) bytes.reserve(static_cast<size_t>(st.st_size));
    char buffer[1 << 16];
    for (;;) {
        const ssize_t n = ::read(fd, buffer, sizeof buffer);
        if (n == 0) break;
        if (n < 0) {
            if (errno == EINTR) continue;
            const int err = errno;
            ::close(fd);
            fail(err);
        }
        bytes.append(buffer, static_cast<size_t>(n));
    }
    ::close(fd);
    return bytes;
}

bool starts_with(std::string_view bytes, std::string_view prefix) {
    return bytes.substr(0, prefix.size()) == prefix;
}

/// Decodes by the file's signature, whatever its extension.
Image decode_any(std::string_view bytes) {
    if (starts_with(bytes, "\x89PNG")) return decode_png(bytes);
    if (starts_with(bytes, "\x76\x2f\x31\x01")) return decode_exr(bytes);
    if (starts_with(bytes, "PF") || starts_with(bytes, "Pf")) return decode_pfm(bytes);
    if (starts_with(bytes, "P")) return decode_ppm(bytes);
    throw ImageError("not a PNG, PPM, PFM or OpenEXR file");
}

}  // namespace

bool format_from_path(const std::string& path, ImageFormat& out) {
    const size_t slash = path.find_last_of('/');
    const size_t dot = path.find_last_of('.');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return false;
    std::string ext = path.substr(dot + 1);
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (ext == "png") {
        out = ImageFormat::png;
    } else if (ext == "ppm") {
        out = ImageFormat::ppm;
    } else if (ext == "pfm") {
        out = ImageFormat::pfm;
    } else if (ext == "exr") {
        out = ImageFormat::exr;
    } else {
        return false;
    }
    return true;
}

uint8_t encode_8bit_srgb(float I) {
    // clamp(I, 0, 1); NaN encodes as 0
    if (!(I > 0.0f)) return 0;
    if (I >= 1.0f) return 255;
    // the sRGB transfer curve (IEC 61966-2-1)
    const double v = I <= 0.0031308 ? 12.92 * I : 1.055 * std::pow(double(I), 1.0 / 2.4) - 0.055;
    return static_cast<uint8_t>(255.0 * v + 0.5);
}

std::string encode_image(const std::string& path, const Image& img, Encoding e) {
    return encode_image_layers(path, img, {}, e);
}

std::string encode_image_layers(const std::string& path, const Image& img,
                                const std::vector<ExrLayer>& layers, Encoding e) {
    ImageFormat format{};
    if (!format_from_path(path, format)) {
        throw ImageError(
            path + ": unknown image format (supported extensions: " + supported_extensions + ")");
    }
    if (img.width <= 0 || img.height <= 0) {
        throw ImageError(path + ": cannot write: the image is empty (" + std::to_string(img.width) +
                         "x" + std::to_string(img.height) + ")");
    }
    if (img.pixels.size() != static_cast<size_t>(img.width) * static_cast<size_t>(img.height)) {
        throw ImageError(path + ": cannot write: the image has " +
                         std::to_string(img.pixels.size()) + " pixels, not " +
                         std::to_string(img.width) + "x" + std::to_string(img.height));
    }

    std::string bytes;
    try {
        switch (format) {
            case ImageFormat::png:
                bytes = encode_png(img, e);
                break;
            case ImageFormat::ppm:
                bytes = encode_ppm(img, e);
                break;
            case ImageFormat::pfm:
                bytes = encode_pfm(img);
                break;
            case ImageFormat::exr:
                bytes = encode_exr_layers(img, layers);
                break;
        }
    } catch (const std::exception& ex) {
        throw ImageError(path + ": cannot write: " + ex.what());
    }
    return bytes;
}

void write_image(const std::string& path, const Image& img, Encoding e) {
    const std::string bytes = encode_image(path, img, e);
    try {
        write_file_atomically(path, bytes);
    } catch (const FileError& ex) {
        throw ImageError(ex.what());
    }
}

Image read_exr_layer(const std::string& path, const std::string& layer) {
    const std::string bytes = read_file(path);
    try {
        return decode_exr_layer(bytes, layer);
    } catch (const std::exception& ex) {
        throw ImageError(path + ": cannot read layer " + layer + ": " + ex.what());
    }
}

Image read_image(const std::string& path) {
    const std::string bytes = read_file(path);
    try {
        return decode_any(bytes);
    } catch (const std::exception& ex) {
        throw ImageError(path + ": cannot read: " + ex.what());
    }
}

}  // namespace luz
