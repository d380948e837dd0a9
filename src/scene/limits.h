// The allowed range of every numeric scene key (docs/SCENES.md#scene-files), in one table
// (limits.cpp; shape keys from shape_desc.h): the loader validates through it and the viewer's
// sliders take their ranges from it.
#pragma once

#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "luz/sliders.h"  // SliderRange, slider_range()

namespace luz {

inline constexpr double kUnbounded = std::numeric_limits<double>::infinity();

/// An allowed interval, open or closed at either end, and the part of it a slider shows.
struct Limit {
    double lo = -kUnbounded, hi = kUnbounded;
    bool lo_open = false, hi_open = false;
    /// The viewer's slider ends: inside the interval, and at its ends where they are finite and
    /// closed; narrower where the interval is open or unbounded (n > 0: 0.1 … 2000).
    double ui_lo = 0, ui_hi = 0;

    constexpr bool contains(double d) const {
        return (lo_open ? d > lo : d >= lo) && (hi_open ? d < hi : d <= hi);
    }
    /// "must be in [0, 1]", "must be > 0", …; empty when unbounded.
    std::string text() const;
};

/// [lo, hi], the slider showing all of it.
constexpr Limit closed(double lo, double hi) { return {lo, hi, false, false, lo, hi}; }
/// ≥ lo; the slider shows lo … ui_hi.
constexpr Limit at_least(double lo, double ui_hi) {
    return {lo, kUnbounded, false, false, lo, ui_hi};
}
/// > lo; the slider shows ui_lo … ui_hi.
constexpr Limit above(double lo, double ui_lo, double ui_hi) {
    return {lo, kUnbounded, true, false, ui_lo, ui_hi};
}
/// (lo, hi); the slider shows ui_lo … ui_hi.
constexpr Limit strictly_between(double lo, double hi, double ui_lo, double ui_hi) {
    return {lo, hi, true, true, ui_lo, ui_hi};
}

/// Any finite number (positions, transforms): no range, no slider.
inline constexpr Limit kAnyNumber{};
/// A shape's size (radius, height): > 0.
inline constexpr Limit kShapeSize = above(0, 0.01, 100);
/// A cone's apex_radius: ≥ 0 (0: a full cone; < radius is checked with the radius).
inline constexpr Limit kApexRadius = at_least(0, 100);

/// How a numeric key is written: a number, an integer, or a colour (a number or 3 numbers,
/// each within the limit).
enum class NumberKind { real, integer, rgb };

/// One row of the table.
struct KeyLimit {
    /// The key path, "*" standing for any array index or material name ("lights.*.radius");
    /// shape keys as "objects.TYPE.KEY" ("objects.sphere.radius").
    std::string key;
    NumberKind kind;
    Limit limit;
};

/// Every numeric scene key with a range: the settings, lights and materials, then the shapes'
/// keys (kShapeKeys).
const std::vector<KeyLimit>& key_limits();

/// The row of `key` (a key path as in key_limits()). Throws std::logic_error when there is none:
/// a programming error.
const KeyLimit& key_limit(std::string_view key);

/// The range a slider for `key` shows (Limit::ui_lo … ui_hi).
SliderRange slider_range(std::string_view key);

/// Largest image, in pixels (image.width · image.height), 2^28.
inline constexpr long long kMaxPixels = 1LL << 28;

}  // namespace luz
