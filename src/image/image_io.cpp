// Image files: picks the format, encodes in memory, and writes atomically (temporary file in the
// same directory, fsync, rename); reads whole files and decodes them by their content.

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

#include "image/image_codecs.h"

namespace luz {
namespace {

constexpr const char* supported_extensions = ".png, .ppm, .pfm, .exr";

/// The text of an errno value ("No such file or directory").
std::string error_text(int err) { return std::error_code(err, std::generic_category()).message(); }

/// A 64-bit value that differs between calls and processes, for temporary file names.
uint64_t random_suffix() {
    static std::atomic<uint64_t> counter{0};
    static const uint64_t seed = [] {
        uint64_t s =
            static_cast<uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count());
        try {
            std::random_device rd;
            s ^= (static_cast<uint64_t>(rd()) << 32) ^ rd();
        } catch (...) {  // no entropy source: time and counter still make names unique enough
        }
        return s;
    }();
    // splitmix64 of seed + counter
    uint64_t z = seed + 0x9e3779b97f4a7c15ULL * (counter.fetch_add(1) + 1);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

/// Writes all of `bytes` to `fd`; false with errno set on failure.
bool write_all(int fd, const std::string& bytes) {
    const char* p = bytes.data();
    size_t left = bytes.size();
    while (left > 0) {
        const ssize_t n = ::write(fd, p, left);
        if (n < 0) {
            if (errno == EINTR) continue;
            return false;
        }
        p += n;
        left -= static_cast<size_t>(n);
    }
    return true;
}

/// Puts `bytes` at `path` atomically: a temporary file `.<name>.tmp.<pid>.<random>` in the same
/// directory is written, flushed to disk and renamed over `path`. On failure the temporary
/// file is removed, `path` is untouched, and ImageError names `path`.
void write_file_atomically(const std::string& path, const std::string& bytes) {
    const size_t slash = path.find_last_of('/');
    const std::string dir = slash == std::string::npos ? "" : path.substr(0, slash + 1);
    std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
    if (name.size() > 100) name.resize(100);  // keep the temporary name under NAME_MAX
    const auto fail = [&path](int err) {
        throw ImageError(path + ": cannot write: " + error_text(err));
    };

    // Create the temporary file (0666 less the umask, as any new file).
    std::string tmp;
    int fd = -1;
    for (int attempt = 0; fd < 0; ++attempt) {
        char suffix[17];
        std::snprintf(suffix, sizeof suffix, "%016llx",
                      static_cast<unsigned long long>(random_suffix()));
        tmp = dir + "." + name + ".tmp." + std::to_string(::getpid()) + "." + suffix;
        fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd < 0 && (errno != EEXIST || attempt >= 100)) fail(errno);
    }

    // Write, flush to disk, close; any error removes the temporary file.
    int err = 0;
    if (!write_all(fd, bytes) || ::fsync(fd) != 0) err = errno;
    if (::close(fd) != 0 && err == 0) err = errno;
    if (err == 0 && ::rename(tmp.c_str(), path.c_str()) != 0) err = errno;
    if (err != 0) {
        ::unlink(tmp.c_str());
        fail(err);
    }

    // Best effort: make the rename itself durable.
    const int dir_fd = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dir_fd >= 0) {
        ::fsync(dir_fd);
        ::close(dir_fd);
    }
}

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

uint8_t encode_8bit(float I, Encoding e) {
    // clamp(I, 0, 1); NaN encodes as 0
    if (!(I > 0.0f)) return 0;
    if (I >= 1.0f) return 255;
    double v = I;
    if (e == Encoding::srgb) {  // the sRGB transfer curve (IEC 61966-2-1)
        v = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
    }
    // round(255·v): the product is exact in double, and v ≥ 0 so +0.5 rounds half up
    return static_cast<uint8_t>(255.0 * v + 0.5);
}

void write_image(const std::string& path, const Image& img, Encoding e) {
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
                bytes = encode_exr(img);
                break;
        }
    } catch (const std::exception& ex) {
        throw ImageError(path + ": cannot write: " + ex.what());
    }
    write_file_atomically(path, bytes);
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
