// Image: a float RGB image in linear values, the output of every pipeline.
#pragma once

#include <vector>

#include "math/vec3.h"

namespace luz {

struct Image {
    int width = 0, height = 0;
    std::vector<Rgb> pixels;  ///< row-major, row 0 at the top

    Image() = default;
    Image(int w, int h, Rgb fill = Rgb{0.0f})
        : width(w), height(h), pixels(static_cast<size_t>(w) * h, fill) {}

    Rgb& at(int x, int y) { return pixels[static_cast<size_t>(y) * width + x]; }
    const Rgb& at(int x, int y) const { return pixels[static_cast<size_t>(y) * width + x]; }
};

}  // namespace luz
