// Image comparison: channel-by-channel differences between two float images, for tests
// (golden images, pipeline agreement, round trips) and regression checks.
#pragma once

#include <cstddef>
#include <string>

#include "image/image.h"

namespace luz {

/// How two images differ. A channel's difference is |a − b| of the stored values; two NaNs or
/// two equal infinities count as equal, a NaN against anything else as an infinite difference.
struct ImageDiff {
    bool same_size = true;       ///< false: sizes differ, max_abs and rmse are infinite
    double max_abs = 0.0;        ///< largest channel difference
    double rmse = 0.0;           ///< root mean square of the channel differences
    int max_x = -1, max_y = -1;  ///< the pixel where max_abs occurs first (-1: none differs)
    int max_channel = -1;        ///< its channel, 0 = R, 1 = G, 2 = B
    size_t pixels = 0;           ///< pixels compared
    size_t pixels_above = 0;     ///< pixels with a channel differing by more than `tolerance`
    float tolerance = 0.0f;      ///< the tolerance pixels_above was counted with

    /// Fraction of pixels whose three channels all differ by at most `tolerance` (1 if none).
    double fraction_within() const {
        if (!same_size) return 0.0;
        return pixels == 0 ? 1.0 : 1.0 - static_cast<double>(pixels_above) / pixels;
    }
};

/// Compares `a` with `b`; `tol` is the tolerance counted in pixels_above.
ImageDiff compare_images(const Image& a, const Image& b, float tol = 0.0f);

/// Largest absolute channel difference (infinity if the sizes differ).
double max_abs_difference(const Image& a, const Image& b);

/// Root mean square of the channel differences (infinity if the sizes differ).
double rms_difference(const Image& a, const Image& b);

/// Fraction of pixels whose three channels all differ by at most `tol` (0 if the sizes differ).
double fraction_within(const Image& a, const Image& b, float tol);

/// One line for a test's failure message, e.g. "max |a-b| 0.25 at (3, 1) channel G,
/// rmse 0.0125, 1 of 64 pixels above 0.01".
std::string to_string(const ImageDiff& d);

}  // namespace luz
