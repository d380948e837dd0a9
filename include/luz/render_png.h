// A render straight to PNG bytes: where it can, the image rendered and compressed band by band
// into one small buffer, without a float image of the whole size (the luz command's -o X.png).
#pragma once

#include <string>

#include "luz/render.h"

namespace luz {

/// What render_png() made: the PNG file's bytes (empty when cancelled) and the statistics.
struct PngFrame {
    std::string png;
    RenderStats stats;
    bool complete = false;
};

/// The image of render(scene, settings, options) as a PNG file with `encoding`, the very bytes
/// encode_frame() gives for it. Where it can (the ray pipelines, each pixel from its own
/// samples, no terms, mask or region asked for), it renders band by band.
PngFrame render_png(const Scene& scene, const Settings& settings, const RenderOptions& options,
                    Encoding encoding);

}  // namespace luz
