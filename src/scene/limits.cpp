// The table of numeric scene keys and their ranges (docs/SCENES.md#scene-files): the one place they
// are written.
#include "scene/limits.h"

#include <cmath>
#include <stdexcept>

#include "scene/number_text.h"
#include "scene/shape_desc.h"

namespace luz {

std::string Limit::text() const {
    const auto g = [](double d) { return format_number(d); };
    const bool has_lo = std::isfinite(lo), has_hi = std::isfinite(hi);
    if (has_lo && has_hi) {
        return std::string("must be in ") + (lo_open ? "(" : "[") + g(lo) + ", " + g(hi) +
               (hi_open ? ")" : "]");
    }
    if (has_lo) return std::string("must be ") + (lo_open ? "> " : ">= ") + g(lo);
    if (has_hi) return std::string("must be ") + (hi_open ? "< " : "<= ") + g(hi);
    return "";
}

namespace {

using enum NumberKind;

std::vector<KeyLimit> build_table() {
    std::vector<KeyLimit> table = {
        {"image.width", integer, closed(1, 65536)},
        {"image.height", integer, closed(1, 65536)},
        {"image.background", rgb, at_least(0, 1)},
        {"camera.view_height", real, above(0, 1e-3, 1e4)},
        {"camera.fov_y", real, strictly_between(0, 180, 1, 170)},
        {"render.max_depth", integer, closed(0, 64)},
        {"render.min_weight", real, closed(0, 1)},
        {"render.tessellation", integer, closed(3, 4096)},
        {"render.antialias.samples", integer, closed(1, 256)},  // and a perfect square
        {"render.antialias.threshold", real, at_least(0, 1)},
        {"render.antialias.max_level", integer, closed(0, 6)},
        {"ambient", rgb, at_least(0, 1000)},
        {"attenuation_k", real, above(0, 1e-3, 1000)},
        {"lights.*.intensity", rgb, at_least(0, 1000)},
        {"lights.*.radius", real, at_least(0, 100)},
        {"materials.*.ka", rgb, closed(0, 1)},
        {"materials.*.kd", rgb, closed(0, 1)},
        {"materials.*.ks", rgb, closed(0, 1)},
        {"materials.*.n", real, above(0, 0.1, 2000)},
        {"materials.*.reflection", real, closed(0, 1)},
        {"materials.*.transparency", real, closed(0, 1)},
        {"materials.*.ior", real, at_least(1, 3)},
        {"materials.*.checker.size", real, above(0, 0.01, 100)},
        {"materials.*.checker.ka", rgb, closed(0, 1)},
        {"materials.*.checker.kd", rgb, closed(0, 1)},
    };
    // The shapes' numeric keys, as their key table gives them.
    for (const ShapeKey& k : kShapeKeys) {
        if (k.kind != ShapeKeyKind::number) continue;
        table.push_back({"objects." + std::string(shape_name(k.type)) + "." + std::string(k.name),
                         real, k.limit});
    }
    return table;
}

}  // namespace

const std::vector<KeyLimit>& key_limits() {
    static const std::vector<KeyLimit> table = build_table();
    return table;
}

const KeyLimit& key_limit(std::string_view key) {
    for (const KeyLimit& row : key_limits()) {
        if (row.key == key) return row;
    }
    throw std::logic_error("no limit for scene key \"" + std::string(key) + "\" in scene/limits");
}

SliderRange slider_range(std::string_view key) {
    const Limit& l = key_limit(key).limit;
    return {l.ui_lo, l.ui_hi, l.hi < kUnbounded};
}

std::vector<SliderKey> slider_keys() {
    std::vector<SliderKey> keys;
    for (const KeyLimit& k : key_limits()) keys.push_back({k.key, k.kind == NumberKind::integer});
    return keys;
}

}  // namespace luz
