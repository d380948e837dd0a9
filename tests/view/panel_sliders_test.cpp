// The viewer panel's slider ranges (app/viewer/panel_sliders.h) against the loader's limits
// table: each slider's range is its key's, its ends are accepted by the loader, and where the
// loader's range is closed the slider reaches its end (no more max depth 16 against 64).
#include "app/viewer/panel_sliders.h"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>

#include "scene/number_text.h"
#include "scene/scene_loader.h"

namespace luz {
namespace {

/// A key path for table key `key` ("lights.*.radius" → "lights.0.radius").
std::string path_of(std::string key) {
    if (const std::size_t star = key.find('*'); star != std::string::npos) {
        key.replace(star, 1, key.rfind("lights", 0) == 0 ? "0" : "m");
    }
    return key;
}

/// True when the loader accepts `value` (JSON) at table key `key`.
bool loader_accepts(std::string_view key, const std::string& value) {
    try {
        parse_scene(R"({"objects": [{"type": "sphere"}]})", "a.json", "",
                    {Override{path_of(std::string(key)), value}});
    } catch (const InputError&) {
        return false;
    }
    return true;
}

std::string json_of(double d, NumberKind kind) {
    return kind == NumberKind::integer ? std::to_string(std::llround(d)) : format_number(d);
}

/// One step outside `d` (integers: 1; numbers: the next float) in direction `dir`.
double step(double d, NumberKind kind, int dir) {
    if (kind == NumberKind::integer) return d + dir;
    return std::nextafter(static_cast<float>(d), dir > 0 ? INFINITY : -INFINITY);
}

TEST(PanelSliders, OneEntryPerSliderInOrder) {
    for (std::size_t i = 0; i < std::size(kPanelSliders); ++i) {
        EXPECT_EQ(static_cast<std::size_t>(kPanelSliders[i].id), i) << kPanelSliders[i].label;
    }
}

TEST(PanelSliders, RangesAgreeWithTheLoader) {
    for (const PanelSliderSpec& s : kPanelSliders) {
        SCOPED_TRACE(std::string(s.key));
        const KeyLimit& row = key_limit(s.key);  // every slider edits a key of the table
        const SliderRange r = panel_slider_range(s.id);
        EXPECT_EQ(r.lo, row.limit.ui_lo);
        EXPECT_EQ(r.hi, row.limit.ui_hi);
        EXPECT_LT(r.lo, r.hi);
        // Both ends are values the loader accepts.
        EXPECT_TRUE(loader_accepts(s.key, json_of(r.lo, row.kind))) << r.lo;
        EXPECT_TRUE(loader_accepts(s.key, json_of(r.hi, row.kind))) << r.hi;
        if (s.id == PanelSlider::samples) {
            // The slider edits s, samples = s²: its ends must be perfect squares.
            EXPECT_EQ(std::pow(std::round(std::sqrt(r.lo)), 2), r.lo);
            EXPECT_EQ(std::pow(std::round(std::sqrt(r.hi)), 2), r.hi);
            EXPECT_FALSE(loader_accepts(s.key, json_of(r.hi + 1, row.kind)));
            continue;
        }
        // Where the loader's range is closed, the slider reaches its end: one step beyond is
        // refused.
        const Limit& l = row.limit;
        if (std::isfinite(l.lo) && !l.lo_open) {
            EXPECT_FALSE(loader_accepts(s.key, json_of(step(r.lo, row.kind, -1), row.kind)))
                << "the slider starts above the loader's lowest value";
        }
        if (std::isfinite(l.hi) && !l.hi_open) {
            EXPECT_FALSE(loader_accepts(s.key, json_of(step(r.hi, row.kind, +1), row.kind)))
                << "the slider stops below the loader's highest value";
        }
    }
}

TEST(PanelSliders, MaxDepthAndTessellationSpanTheLoadersRange) {
    // The ranges the panel used to restate differently (16 and 512).
    const SliderRange depth = panel_slider_range(PanelSlider::max_depth);
    EXPECT_TRUE(loader_accepts("render.max_depth", std::to_string(std::llround(depth.hi))));
    EXPECT_FALSE(loader_accepts("render.max_depth", std::to_string(std::llround(depth.hi) + 1)));
    const SliderRange tess = panel_slider_range(PanelSlider::tessellation);
    EXPECT_FALSE(loader_accepts("render.tessellation", std::to_string(std::llround(tess.hi) + 1)));
    EXPECT_FALSE(loader_accepts("render.tessellation", std::to_string(std::llround(tess.lo) - 1)));
}

}  // namespace
}  // namespace luz
