// Image comparison: per-channel absolute differences, their maximum, RMS and the pixels above a
// tolerance.

#include "image/compare.h"

#include <cmath>
#include <cstdio>
#include <limits>

namespace luz {
namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();

/// |a − b|, with NaN equal to NaN and different from everything else.
double channel_difference(float a, float b) {
    if (a == b) return 0.0;  // also equal infinities
    const bool nan_a = std::isnan(a), nan_b = std::isnan(b);
    if (nan_a || nan_b) return nan_a && nan_b ? 0.0 : infinity;
    return std::fabs(static_cast<double>(a) - static_cast<double>(b));
}

}  // namespace

ImageDiff compare_images(const Image& a, const Image& b, float tol) {
    ImageDiff d;
    d.tolerance = tol;
    if (a.width != b.width || a.height != b.height || a.pixels.size() != b.pixels.size()) {
        d.same_size = false;
        d.max_abs = d.rmse = infinity;
        return d;
    }
    d.pixels = a.pixels.size();
    double sum_sq = 0.0;
    for (int y = 0; y < a.height; ++y) {
        for (int x = 0; x < a.width; ++x) {
            const Rgb& pa = a.at(x, y);
            const Rgb& pb = b.at(x, y);
            bool above = false;
            for (int c = 0; c < 3; ++c) {
                const double diff = channel_difference(pa[c], pb[c]);
                sum_sq += diff * diff;
                above = above || diff > tol;
                if (diff > d.max_abs) {
                    d.max_abs = diff;
                    d.max_x = x;
                    d.max_y = y;
                    d.max_channel = c;
                }
            }
            if (above) ++d.pixels_above;
        }
    }
    d.rmse = d.pixels == 0 ? 0.0 : std::sqrt(sum_sq / (3.0 * static_cast<double>(d.pixels)));
    return d;
}

double max_abs_difference(const Image& a, const Image& b) { return compare_images(a, b).max_abs; }

double rms_difference(const Image& a, const Image& b) { return compare_images(a, b).rmse; }

double fraction_within(const Image& a, const Image& b, float tol) {
    return compare_images(a, b, tol).fraction_within();
}

std::string to_string(const ImageDiff& d) {
    char line[200];
    if (!d.same_size) return "images differ in size";
    if (d.max_x < 0) {
        std::snprintf(line, sizeof line, "identical (%zu pixels)", d.pixels);
    } else {
        std::snprintf(line, sizeof line,
                      "max |a-b| %.6g at (%d, %d) channel %c, rmse %.6g, %zu of %zu pixels "
                      "above %.6g",
                      d.max_abs, d.max_x, d.max_y, "RGB"[d.max_channel], d.rmse, d.pixels_above,
                      d.pixels, static_cast<double>(d.tolerance));
    }
    return line;
}

}  // namespace luz
