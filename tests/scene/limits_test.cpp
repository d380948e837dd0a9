// The limits table (scene/limits.h) against the loader: every numeric key with a range accepts
// a value at each finite end of it (or just inside an open end) and refuses one just outside.
#include "scene/limits.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>

#include "scene/number_text.h"
#include "scene/scene_loader.h"

namespace luz {
namespace {

/// A scene key path for table key `key` ("lights.*.radius" → "lights.0.radius",
/// "objects.torus.minor_radius" → "objects.0.minor_radius") and the scene it applies to.
struct Target {
    std::string path, scene;
};
Target target_of(const std::string& key) {
    std::string scene = R"({"objects": [{"type": "sphere"}]})";
    std::string path = key;
    if (key.rfind("objects.", 0) == 0) {
        const std::size_t dot = key.find('.', 8);
        scene = R"({"objects": [{"type": ")" + key.substr(8, dot - 8) + R"("}]})";
        path = "objects.0" + key.substr(dot);
    }
    if (const std::size_t star = path.find('*'); star != std::string::npos) {
        path.replace(star, 1, path.rfind("lights", 0) == 0 ? "0" : "m");
    }
    return {path, scene};
}

/// The loader's message for `value` at `key`, or nullopt when it accepts the scene.
std::optional<std::string> load_with(const std::string& key, const std::string& value) {
    const Target t = target_of(key);
    try {
        parse_scene(t.scene, "a.json", "", {Override{t.path, value}});
    } catch (const InputError& e) {
        return std::string(e.what());
    }
    return std::nullopt;
}

/// What the loader says of a value outside `row`'s range.
std::string refusal(const KeyLimit& row, const std::string& value) {
    const Target t = target_of(row.key);
    if (row.key == "render.antialias.samples") {
        return "--set " + t.path + "=" + value +
               ": must be a perfect square in [1, 256] (1, 4, 9, 16, ...), got " + value;
    }
    return "--set " + t.path + "=" + value + ": " + row.limit.text() + ", got " + value;
}

/// True when the loader accepts `value` as far as `row`'s range goes (a check across keys, such
/// as a torus's minor_radius < major_radius, may still refuse it).
bool accepted(const KeyLimit& row, const std::string& value) {
    const std::optional<std::string> message = load_with(row.key, value);
    return !message || message->find(row.limit.text() + ", got") == std::string::npos;
}

/// A float `steps` representable floats away from `d` (towards +inf when steps > 0), as JSON.
std::string float_step(double d, int steps) {
    float f = static_cast<float>(d);
    for (int i = 0; i < std::abs(steps); ++i) {
        f = std::nextafter(f, steps > 0 ? INFINITY : -INFINITY);
    }
    return format_number(static_cast<double>(f));
}

TEST(Limits, EveryRowIsCheckedAtItsEndsByTheLoader) {
    int ends = 0;
    for (const KeyLimit& row : key_limits()) {
        SCOPED_TRACE(row.key);
        const Limit& l = row.limit;
        const bool integer = row.kind == NumberKind::integer;
        for (const bool low : {true, false}) {
            const double end = low ? l.lo : l.hi;
            if (!std::isfinite(end)) continue;
            ++ends;
            const bool is_open = low ? l.lo_open : l.hi_open;
            const int inward = low ? 1 : -1;
            const std::string at =
                integer ? std::to_string(static_cast<long long>(end)) : format_number(end);
            std::string inside = at, outside;
            if (integer) {
                ASSERT_FALSE(is_open) << "integer ranges are closed";
                outside = std::to_string(static_cast<long long>(end) - inward);
            } else if (is_open) {
                inside = float_step(end, inward);
                outside = at;
            } else {
                outside = float_step(end, -inward);
            }
            EXPECT_TRUE(accepted(row, inside)) << inside << ": " << *load_with(row.key, inside);
            EXPECT_EQ(load_with(row.key, outside).value_or("accepted"), refusal(row, outside));
        }
    }
    EXPECT_GE(ends, 30);
}

TEST(Limits, RangesHoldTheirSliderRanges) {
    for (const KeyLimit& row : key_limits()) {
        SCOPED_TRACE(row.key);
        const Limit& l = row.limit;
        EXPECT_LE(l.ui_lo, l.ui_hi);
        EXPECT_TRUE(l.contains(l.ui_lo) && l.contains(l.ui_hi));
        if (std::isfinite(l.lo) && !l.lo_open) {
            EXPECT_EQ(l.ui_lo, l.lo);
        }
        if (std::isfinite(l.hi) && !l.hi_open) {
            EXPECT_EQ(l.ui_hi, l.hi);
        }
    }
}

TEST(Limits, TheLoadersKnownRanges) {
    // A few rows written out: the table says what the loader said before it existed.
    EXPECT_EQ(key_limit("render.max_depth").limit.hi, 64);
    EXPECT_EQ(key_limit("render.tessellation").limit.lo, 3);
    EXPECT_EQ(key_limit("render.tessellation").limit.hi, 4096);
    EXPECT_EQ(key_limit("render.antialias.max_level").limit.hi, 6);
    EXPECT_EQ(key_limit("materials.*.n").limit.text(), "must be > 0");
    EXPECT_EQ(key_limit("materials.*.ior").limit.text(), "must be >= 1");
    EXPECT_EQ(key_limit("camera.fov_y").limit.text(), "must be in (0, 180)");
    EXPECT_EQ(key_limit("objects.torus.minor_radius").limit.text(), "must be > 0");
    EXPECT_THROW(key_limit("objects.sphere.center"), std::logic_error);
}

}  // namespace
}  // namespace luz
