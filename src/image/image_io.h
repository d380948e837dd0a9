// Image files: PNG and PPM (8-bit, linear or sRGB encoded), PFM and EXR (float, unclamped).
// Writers go through a temporary file renamed into place, so a failure never leaves a partial
// file and never truncates an existing one.
#pragma once

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "image/image.h"
#include "scene/scene_desc.h"

namespace luz {

enum class ImageFormat { png, ppm, pfm, exr };

/// A further layer of an EXR file (encode_exr_layers): channels NAME.R/G/B, or NAME.Y alone.
struct ExrLayer {
    std::string name;
    const Image* image = nullptr;
    bool scalar = false;
};

/// Reads layer `layer` of an EXR file (LAYER.R/G/B or LAYER.Y); for tests.
Image read_exr_layer(const std::string& path, const std::string& layer);

/// Raised when an image cannot be written or read; the message names the file.
struct ImageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// The format for a file name by its extension (case-insensitive); false if unknown.
bool format_from_path(const std::string& path, ImageFormat& out);

/// 8-bit sRGB value of a linear intensity: round(255·srgb(clamp(I,0,1))); NaN gives 0.
uint8_t encode_8bit_srgb(float I);

/// 8-bit value of a linear intensity: linear round(255·clamp(I,0,1)), or the sRGB curve;
/// NaN gives 0. Inline: it runs for every channel of every pixel written.
inline uint8_t encode_8bit(float I, Encoding e) {
    if (e == Encoding::srgb) return encode_8bit_srgb(I);
    if (!(I > 0.0f)) return 0;
    if (I >= 1.0f) return 255;
    // round(255·I): the product is exact in double, and I > 0 so +0.5 rounds half up
    return static_cast<uint8_t>(255.0 * double(I) + 0.5);
}

/// The bytes of `img` in the format its extension names, as write_image would write them (for
/// files committed together with others, see atomic_file.h); throws ImageError naming `path`,
/// or Cancelled once the calling thread's cancel flag (scene/cancel.h) is set.
std::string encode_image(const std::string& path, const Image& img, Encoding e = Encoding::linear);

/// The same with further EXR layers (ignored by the other formats: only .exr holds layers).
std::string encode_image_layers(const std::string& path, const Image& img,
                                const std::vector<ExrLayer>& layers, Encoding e = Encoding::linear);

/// A PNG file (8-bit RGB, as encode_image writes it: the very bytes) from rows given band by
/// band, each quantized and compressed when given (in parallel), so that a render can hand its
/// rows over as it finishes them and never hold the whole image in float.
///     PngBands png(w, h, encoding);
///     png.add(rows, n);  // the next n rows: rows.at(x, r) for r < n, in order
///     std::string bytes = png.finish();
/// Every add() but the one giving the last rows takes a multiple of kBandRows rows.
class PngBands {
  public:
    static constexpr int kBandRows = 64;  ///< rows deflated together (any thread count)
    PngBands(int width, int height, Encoding e);
    ~PngBands();
    /// Rows 0 … count − 1 of `rows` (its width is the image's) as the image's next rows;
    /// throws ImageError when they do not fit.
    void add(const Image& rows, int count);
    /// The file's bytes once every row has been given; throws ImageError.
    std::string finish();

  private:
    struct Bands;
    int width_, height_, done_ = 0;
    Encoding encoding_;
    std::unique_ptr<Bands> bands_;
};

/// Writes `img` to `path` in the format its extension names, atomically.
void write_image(const std::string& path, const Image& img, Encoding e = Encoding::linear);

/// Reads a PNG, PPM, PFM or EXR file (8-bit values become v/255, not decoded); for tests
/// and image comparison.
Image read_image(const std::string& path);

}  // namespace luz
