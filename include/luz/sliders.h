// The sliders of the viewer's panel and the web page's: which numeric scene keys have one, and
// the range each shows (the loader's limits for the key).
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace luz {

/// The range a slider of the scene key `key` (e.g. "render.max_depth", "materials.*.n") shows:
/// within the loader's limits for that key.
struct SliderRange {
    double lo, hi;
    bool capped = false;  ///< the key has an upper limit: a typed-in value stays ≤ hi
};
SliderRange slider_range(std::string_view key);

/// A numeric scene key that has a slider: its path ("lights.*.radius", "objects.sphere.radius")
/// and whether it takes whole numbers.
struct SliderKey {
    std::string key;
    bool integer = false;
};
/// Every numeric scene key with a range, in the loader's order (the web page's panel).
std::vector<SliderKey> slider_keys();

}  // namespace luz
