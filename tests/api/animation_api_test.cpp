// Animations in the public API (include/luz/animation.h): Animation::load and its frames, each
// frame the scene with its keyed values set (rendered bit for bit the same), --frames ranges,
// frame file names and the statistics of a sequence.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <charconv>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "luz/animation.h"
#include "luz/luz.h"
#include "luz/scene_text.h"
#include "same_bits.h"

namespace luz {
namespace {

using nlohmann::json;
using ::testing::HasSubstr;

/// The shortest text that reads back as `v`.
template <typename T>
std::string text_of(T v) {
    char buffer[64];
    return std::string(buffer, std::to_chars(buffer, buffer + sizeof buffer, v).ptr);
}

/// What `animation.keys` give at frame `f`, computed here on their own (linear between
/// keyframes, held outside), as --set arguments.
std::vector<std::string> keyed_sets(const json& keys, int f) {
    std::vector<std::string> out;
    for (const auto& [path, frames] : keys.items()) {
        const auto at = [&](std::size_t c) {
            const auto value = [&](std::size_t i) {
                const json& v = frames[i][1];
                return v.is_array() ? v[c].get<double>() : v.get<double>();
            };
            if (f <= frames.front()[0].get<int>()) return value(0);
            for (std::size_t i = 1; i < frames.size(); ++i) {
                const int f0 = frames[i - 1][0], f1 = frames[i][0];
                if (f == f1) return value(i);
                const double t = double(f - f0) / double(f1 - f0);
                if (f < f1) return value(i - 1) + (value(i) - value(i - 1)) * t;
            }
            return value(frames.size() - 1);
        };
        const json& first = frames.front()[1];
        std::string v;
        if (first.is_array()) {
            v = "[";
            for (std::size_t c = 0; c < first.size(); ++c) v += (c ? "," : "") + text_of(at(c));
            v += "]";
        } else {
            v = text_of(at(0));
        }
        out.push_back(path + "=" + v);
    }
    return out;
}

std::vector<Override> overrides(const std::vector<std::string>& sets) {
    std::vector<Override> out;
    for (const std::string& s : sets) out.push_back(parse_set(s));
    return out;
}

const std::vector<std::string> kSmall = {"image.width=32", "image.height=24",
                                         "render.pipeline=raycast"};

Image render_image(const SceneDesc& d) {
    RenderOptions o;
    o.threads = 2;
    const Frame f = render(build(d), d, o);
    EXPECT_TRUE(f.complete);
    return f.image;
}

/// Each test in its own folder for the scene files it writes.
class AnimationApi : public testing::Test {
  protected:
    void SetUp() override {
        dir_ = std::filesystem::temp_directory_path() /
               ("luz_animation_api_" + std::to_string(::getpid()) + "_" +
                testing::UnitTest::GetInstance()->current_test_info()->name());
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }
    std::string write(const std::string& name, const std::string& text) {
        std::ofstream((dir_ / name)) << text;
        return (dir_ / name).string();
    }
    std::filesystem::path dir_;
};

const char* const kScene = R"({
  "image": {"width": 64, "height": 48},
  "camera": {"projection": "perspective", "position": [0, 1.5, 6], "look_at": [0, 0.8, 0]},
  "materials": {"red": {"ka": 0.1, "kd": [0.7, 0.1, 0.1], "ks": 0.4, "n": 3}},
  "lights": [{"position": [-5, 5, 5], "intensity": 9}],
  "objects": [{"type": "plane", "material": "gesso"},
              {"type": "sphere", "center": [0, 1, 0], "material": "red"}]
})";

/// kScene with an `animation`.
std::string animated(const json& animation) {
    json j = json::parse(kScene);
    j["animation"] = animation;
    return j.dump(2);
}

const json kAnimation = json::parse(R"({"frames": 9, "fps": 12, "keys": {
    "materials.red.n": [[0, 1], [3, 7], [8, 100]],
    "lights.0.position": [[1, [-5, 5, 5]], [7, [5, 3, 4]]],
    "objects.1.radius": [[0, 0.5], [8, 1.2]]}})");

TEST_F(AnimationApi, LoadKnowsTheFramesAndFps) {
    const Animation a = Animation::load(write("a.json", animated(kAnimation)), {});
    EXPECT_TRUE(a.animated());
    EXPECT_EQ(a.frames(), 9);
    EXPECT_EQ(a.fps(), 12);
    EXPECT_EQ(a.first().frame, 0);
    EXPECT_EQ(a.first().name, "a");

    const Animation h = Animation::load("demo:highlight", {});
    EXPECT_TRUE(h.animated());
    EXPECT_EQ(h.frames(), 48);
    EXPECT_EQ(h.fps(), 24);

    // No animation: one frame, the scene itself.
    const Animation still = Animation::load(write("still.json", kScene), {});
    EXPECT_FALSE(still.animated());
    EXPECT_EQ(still.frames(), 1);
    EXPECT_EQ(still.frame(0).frame, 0);
    EXPECT_THROW(still.frame(1), SceneError);

    // --set before the animation is read: it may change it.
    const Animation more = Animation::load(write("b.json", animated(kAnimation)),
                                           overrides({"animation.frames=20", "animation.fps=30"}));
    EXPECT_EQ(more.frames(), 20);
    EXPECT_EQ(more.fps(), 30);
    EXPECT_EQ(more.frame(19).frame, 19);
    EXPECT_THROW(more.frame(20), SceneError);
    EXPECT_THROW(more.frame(-1), SceneError);
}

TEST_F(AnimationApi, LoadChecksEveryFrame) {
    json bad = kAnimation;
    bad["keys"]["objects.1.radius"] = json::parse("[[0, 1], [6, 1], [7, -1]]");
    try {
        Animation::load(write("bad.json", animated(bad)), {});
        FAIL() << "frame 7 has a negative radius";
    } catch (const SceneError& e) {
        EXPECT_EQ(std::string(e.what()), (dir_ / "bad.json").string() +
                                             ": animation.keys.objects.1.radius at frame 7 = -1: "
                                             "objects.1.radius: must be > 0, got -1");
    }
}

TEST_F(AnimationApi, FrameIsTheSceneWithItsKeyedValuesSet) {
    const std::string file = write("a.json", animated(kAnimation));
    const std::string still = write("still.json", kScene);
    const Animation a = Animation::load(file, overrides(kSmall));
    for (int f : {0, 1, 2, 3, 5, 8}) {
        SCOPED_TRACE("frame " + std::to_string(f));
        std::vector<std::string> sets = kSmall;
        for (const std::string& s : keyed_sets(kAnimation["keys"], f)) sets.push_back(s);
        const SceneDesc expected = load_scene(still, overrides(sets));
        const SceneDesc d = a.frame(f);
        EXPECT_EQ(d.frame, f);
        EXPECT_EQ(d.image.width, 32);
        EXPECT_TRUE(same_bits(render_image(d), render_image(expected)));
    }
    // The frames differ from one another.
    EXPECT_FALSE(same_bits(render_image(a.frame(2)), render_image(a.frame(5))));
}

TEST_F(AnimationApi, HighlightFramesAreTheDemoWithItsKeyedValuesSet) {
    // demo:highlight without its animation, then the keyed values by --set.
    const SceneText t = read_scene_text("demo:highlight");
    json j = json::parse(t.text);
    const json keys = j["animation"]["keys"];
    j.erase("animation");
    const std::string still = j.dump();
    const Animation a = Animation::load("demo:highlight", overrides(kSmall));
    for (int f : {0, 12, 30, 47}) {
        SCOPED_TRACE("frame " + std::to_string(f));
        std::vector<std::string> sets = kSmall;
        for (const std::string& s : keyed_sets(keys, f)) sets.push_back(s);
        const SceneDesc expected = parse_scene(still, "demo:highlight", "", overrides(sets));
        EXPECT_TRUE(same_bits(render_image(a.frame(f)), render_image(expected)));
    }
}

TEST_F(AnimationApi, OrbitFrameIsTheSceneWithTheCameraMoved) {
    // No lights: the implicit light at the camera's upper left turns with the camera.
    json j = json::parse(kScene);
    j.erase("lights");
    const std::string still = write("still.json", j.dump());
    j["animation"] = json::parse(R"({"frames": 6, "orbit": 90})");
    const Animation a = Animation::load(write("orbit.json", j.dump()), overrides(kSmall));
    for (int f : {1, 3, 5}) {
        SCOPED_TRACE("frame " + std::to_string(f));
        const SceneDesc d = a.frame(f);
        const Vec3 p = d.camera.position;
        std::vector<std::string> sets = kSmall;
        sets.push_back("camera.position=[" + text_of(p.x) + "," + text_of(p.y) + "," +
                       text_of(p.z) + "]");
        const SceneDesc expected = load_scene(still, overrides(sets));
        EXPECT_EQ(length(expected.camera.position - d.camera.position), 0.0f);
        EXPECT_TRUE(same_bits(render_image(d), render_image(expected)));
    }
}

TEST_F(AnimationApi, FramesShareTheMeshesReadByLoad) {
    std::ofstream(dir_ / "tri.obj") << "v -1 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    const std::string file = write("m.json", R"({
      "objects": [{"type": "mesh", "file": "tri.obj", "transform": {"rotate": [0, 0, 0]}}],
      "animation": {"frames": 5, "keys": {"objects.0.transform.rotate": [[0, [0, 0, 0]],
                                                                          [4, [0, 90, 0]]]}}})");
    const Animation a = Animation::load(file, {});
    ASSERT_NE(a.first().objects[0].mesh, nullptr);
    std::filesystem::remove(dir_ / "tri.obj");  // not read again
    for (int f = 1; f < 5; ++f) EXPECT_EQ(a.frame(f).objects[0].mesh, a.first().objects[0].mesh);
}

// --- parse_frames -------------------------------------------------------------------------------

TEST_F(AnimationApi, ParseFramesTakesARangeOrAll) {
    const Animation a = Animation::load(write("a.json", animated(kAnimation)), {});
    const FrameRange r = parse_frames("0:3", a);
    EXPECT_EQ(r.first, 0);
    EXPECT_EQ(r.end, 3);
    EXPECT_EQ(r.count(), 3);
    const FrameRange all = parse_frames("all", a);
    EXPECT_EQ(all.first, 0);
    EXPECT_EQ(all.end, 9);
    const FrameRange last = parse_frames("8:9", a);
    EXPECT_EQ(last.first, 8);
    EXPECT_EQ(last.count(), 1);
    EXPECT_EQ(parse_frames("0:9", a).count(), 9);
}

TEST_F(AnimationApi, ParseFramesRefusesBadRangesNamingTheOption) {
    const Animation a = Animation::load(write("a.json", animated(kAnimation)), {});
    const std::pair<const char*, const char*> cases[] = {
        {"3:3", "--frames 3:3: empty range: B must be greater than A"},
        {"2:1", "--frames 2:1: empty range: B must be greater than A"},
        {"0:999", "--frames 0:999: past the last frame: the scene has frames 0 to 8, so B ≤ 9"},
        {"0:10", "--frames 0:10: past the last frame"},
        {"a:b", "--frames a:b: expected A:B (frames A to B-1) or all, e.g. 0:9"},
        {"1", "--frames 1: expected A:B"},
        {"", "--frames : expected A:B"},
        {":3", "--frames :3: expected A:B"},
        {"0:", "--frames 0:: expected A:B"},
        {"-1:3", "--frames -1:3: expected A:B"},
        {"0:3x", "--frames 0:3x: expected A:B"},
        {"0:3:5", "--frames 0:3:5: expected A:B"},
        {"ALL", "--frames ALL: expected A:B"},
        {"0:99999999999", "--frames 0:99999999999: expected A:B"},
    };
    for (const auto& [text, message] : cases) {
        try {
            parse_frames(text, a);
            ADD_FAILURE() << "accepted: " << text;
        } catch (const SceneError& e) {
            EXPECT_THAT(e.what(), HasSubstr(message)) << text;
            EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
        }
    }
    // Another front end names its own argument.
    try {
        parse_frames("5:2", a, "frames=");
        ADD_FAILURE() << "accepted";
    } catch (const SceneError& e) {
        EXPECT_THAT(e.what(), HasSubstr("frames= 5:2: empty range"));
    }
}

TEST_F(AnimationApi, ParseFramesNeedsAnAnimation) {
    const std::string still = write("still.json", kScene);
    const Animation a = Animation::load(still, {});
    for (const char* text : {"0:1", "all"}) {
        try {
            parse_frames(text, a);
            ADD_FAILURE() << "accepted: " << text;
        } catch (const SceneError& e) {
            EXPECT_EQ(std::string(e.what()), std::string("--frames ") + text + ": " + still +
                                                 " has no animation (add an \"animation\" key, "
                                                 "docs/SCENES.md#scene-files)");
        }
    }
}

// --- frame_path ---------------------------------------------------------------------------------

TEST(AnimationFramePath, NumberGoesBeforeTheExtension) {
    EXPECT_EQ(frame_path("out/x.png", 7), "out/x.0007.png");
    EXPECT_EQ(frame_path("out/x.png", 0), "out/x.0000.png");
    EXPECT_EQ(frame_path("out/x.png", 9999), "out/x.9999.png");
    EXPECT_EQ(frame_path("out/x.png", 12345), "out/x.12345.png");
    EXPECT_EQ(frame_path("x.pfm", 42), "x.0042.pfm");
    EXPECT_EQ(frame_path("/tmp/a.b/c.d.exr", 3), "/tmp/a.b/c.d.0003.exr");
    EXPECT_EQ(frame_path("x", 3), "x.0003");
}

// --- animation_stats_json -----------------------------------------------------------------------

RenderStats stats_of(uint64_t primary, uint64_t shadow, double seconds, uint64_t memory) {
    RenderStats s;
    s.width = 32;
    s.height = 24;
    s.threads = 2;
    s.rays_primary = primary;
    s.rays_shadow = shadow;
    s.tests_primitive = 10 * primary;
    s.seconds = seconds;
    s.peak_memory_bytes = memory;
    s.bvh_nodes = 7;
    return s;
}

TEST_F(AnimationApi, StatsHoldTheTotalsAndEveryFrame) {
    const Animation a = Animation::load(write("a.json", animated(kAnimation)), overrides(kSmall));
    const std::vector<RenderStats> stats = {stats_of(768, 100, 0.5, 1000),
                                            stats_of(768, 300, 0.25, 3000),
                                            stats_of(800, 5, 0.125, 2000)};
    const json j = json::parse(animation_stats_json(stats, {2, 3, 4}, a.first()));
    EXPECT_EQ(j["rays"]["primary"], 768 + 768 + 800);
    EXPECT_EQ(j["rays"]["shadow"], 405);
    EXPECT_EQ(j["intersection_tests"]["primitive"], 23360);
    EXPECT_DOUBLE_EQ(j["seconds"].get<double>(), 0.875);
    EXPECT_EQ(j["peak_memory_bytes"], 3000);  // the largest, not the sum
    EXPECT_EQ(j["bvh_nodes"], 7);
    EXPECT_EQ(j["width"], 32);
    EXPECT_EQ(j["height"], 24);
    EXPECT_EQ(j["pipeline"], "raycast");
    EXPECT_EQ(j["scene"], a.first().source);
    EXPECT_EQ(j["fps"], 12);
    EXPECT_EQ(j["frame_range"], json::array({2, 5}));
    ASSERT_TRUE(j["frames"].is_array());
    ASSERT_EQ(j["frames"].size(), 3u);
    for (int i = 0; i < 3; ++i) {
        const json& f = j["frames"][i];
        EXPECT_EQ(f["frame"], 2 + i);
        EXPECT_EQ(f["rays"]["primary"], stats[i].rays_primary);
        EXPECT_EQ(f["rays"]["shadow"], stats[i].rays_shadow);
        EXPECT_EQ(f["peak_memory_bytes"], stats[i].peak_memory_bytes);
        EXPECT_DOUBLE_EQ(f["seconds"].get<double>(), stats[i].seconds);
        EXPECT_FALSE(f.contains("scene"));
    }
}

TEST_F(AnimationApi, StatsOfRenderedFramesAddUp) {
    const Animation a = Animation::load(write("a.json", animated(kAnimation)), overrides(kSmall));
    std::vector<RenderStats> stats;
    uint64_t shadow = 0;
    for (int f = 0; f < 3; ++f) {
        const SceneDesc d = a.frame(f);
        stats.push_back(render(build(d), d).stats);
        shadow += stats.back().rays_shadow;
    }
    const json j = json::parse(animation_stats_json(stats, {0, 1, 2}, a.first()));
    EXPECT_EQ(j["rays"]["primary"], 3 * 32 * 24);
    EXPECT_EQ(j["rays"]["shadow"], shadow);
    ASSERT_EQ(j["frames"].size(), 3u);
    EXPECT_EQ(j["frames"][2]["frame"], 2);
    EXPECT_EQ(j["frames"][2]["rays"]["primary"], 32 * 24);
}

}  // namespace
}  // namespace luz
