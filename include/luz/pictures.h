// The 8-bit pictures a front end shows (the viewer's texture, the web page's canvas, `--aa-mask`):
// a per-term image as a picture, the antialiasing mask, an image as RGBA bytes.
#pragma once

#include <cstdint>
#include <vector>

#include "luz/render.h"

namespace luz {

/// The 8-bit picture of a per-term image: colour terms as they are; depth near bright (the
/// nearest hit white, the farthest dark, misses black); normal as 0.5 + 0.5·N; tests through
/// a perceptual colour map (viridis) from 0 to the frame's largest count.
Image aov_picture(const Aov& aov);

/// The --aa-mask picture of a frame rendered with RenderOptions::want_aa_mask.
Image frame_aa_mask(const Frame& frame);

/// The image as 8-bit RGBA bytes (alpha 255), row 0 first, its values encoded as the 8-bit
/// files encode them (e.g. for a texture).
std::vector<uint8_t> rgba8(const Image& image, Encoding encoding);

}  // namespace luz
