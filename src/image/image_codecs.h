// Image codecs (internal to the image layer): each format turns an Image into the bytes of a
// file and back, in memory; image_io.cpp does the file handling and names the file in errors.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "image/image.h"
#include "image/image_io.h"
#include "scene/scene_desc.h"

namespace luz {

// Every function here throws ImageError (or std::bad_alloc) with a message that does not name
// the file: the caller prefixes it. Encoders expect a non-empty, consistent image, and stop
// with Cancelled (scene/cancel.h) within a band of rows once the calling thread's cancel flag
// is set.

/// PNG, 8-bit RGB, values from encode_8bit; an sRGB chunk only when `e` is srgb.
std::string encode_png(const Image& img, Encoding e);
/// PNG of any colour type and bit depth: alpha dropped, grey replicated, values v/(2^bits − 1).
Image decode_png(std::string_view bytes);

/// Binary PPM (P6), maxval 255, values from encode_8bit.
std::string encode_ppm(const Image& img, Encoding e);
/// Binary PPM (P6), any maxval up to 65535: values v/maxval.
Image decode_ppm(std::string_view bytes);

/// PFM: "PF\n<w> <h>\n-1.0\n", little-endian float32 RGB, rows from the bottom up; unclamped.
std::string encode_pfm(const Image& img);
/// PFM, colour (PF) or grey (Pf), either byte order (by the sign of the scale).
Image decode_pfm(std::string_view bytes);

/// OpenEXR, 32-bit FLOAT channels R, G, B, ZIP compression (lossless); unclamped.
std::string encode_exr(const Image& img);
/// The same with further layers: NAME.R, NAME.G, NAME.B, or NAME.Y alone for a scalar layer
/// (its value read from the first channel). Every layer has the image's size.
std::string encode_exr_layers(const Image& img, const std::vector<ExrLayer>& layers);
/// OpenEXR: channels R, G, B (or Y alone) of the data window, as float.
Image decode_exr(std::string_view bytes);
/// The same for layer `layer` (channels LAYER.R, LAYER.G, LAYER.B or LAYER.Y); "" is the image.
Image decode_exr_layer(std::string_view bytes, const std::string& layer);

}  // namespace luz
