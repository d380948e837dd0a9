// Bad animations (docs/SCENES.md#scene-files `animation`) refused with a message naming the key
// path and the frame; errors between keyframes found at load; a bad --set on the animation.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <ostream>
#include <string>

#include "animation_fixtures.h"

namespace luz {
namespace {

using test::frame_of;
using test::material;
using test::parse;
using test::scene_with;
using test::sets;
using ::testing::HasSubstr;

struct BadAnimation {
    const char* animation;  // the `animation` value of scene_with()
    const char* expected;   // what the message holds after "scenes/a.json: "
};

void PrintTo(const BadAnimation& c, std::ostream* os) { *os << c.animation << " → " << c.expected; }

class BadAnimationTest : public ::testing::TestWithParam<BadAnimation> {};

TEST_P(BadAnimationTest, IsRefusedNamingTheKeyPath) {
    const BadAnimation& c = GetParam();
    try {
        parse(scene_with(c.animation));
        FAIL() << "accepted: " << c.animation;
    } catch (const InputError& e) {
        const std::string msg = e.what();
        EXPECT_THAT(msg, HasSubstr(std::string("scenes/a.json: ") + c.expected));
        EXPECT_EQ(msg.find('\n'), std::string::npos) << "one line: " << msg;
    }
}

const BadAnimation kBadAnimations[] = {
    // Paths that are not in the scene.
    {R"({"frames": 3, "keys": {"materials.red.nn": [[0, 1], [2, 2]]}})",
     "animation.keys.materials.red.nn at frame 0 = 1: materials.red.nn: unknown key"},
    {R"({"frames": 3, "keys": {"camra.position": [[0, [1, 2, 3]]]}})",
     "animation.keys.camra.position at frame 0 = [1, 2, 3]: camra: unknown key"},
    {R"({"frames": 3, "keys": {"lights.3.position": [[0, [1, 2, 3]]]}})",
     "animation.keys.lights.3.position at frame 0 = [1, 2, 3]: index 3 is past the end of lights"},
    {R"({"frames": 3, "keys": {"objects.0.material.x": [[0, 1]]}})",
     "animation.keys.objects.0.material.x at frame 0 = 1: objects.0.material is"},
    {R"({"frames": 3, "keys": {"animation.frames": [[0, 3]]}})",
     "animation.keys.animation.frames: the animation cannot animate itself"},
    // Keyframe frames.
    {R"({"frames": 4, "keys": {"objects.0.radius": [[2, 1], [2, 2]]}})",
     "animation.keys.objects.0.radius.1.0: keyframes must be in increasing frame order: frame 2 "
     "after frame 2"},
    {R"({"frames": 4, "keys": {"objects.0.radius": [[0, 1], [3, 2], [1, 3]]}})",
     "animation.keys.objects.0.radius.2.0: keyframes must be in increasing frame order: frame 1 "
     "after frame 3"},
    {R"({"frames": 4, "keys": {"objects.0.radius": [[1.5, 1]]}})",
     "animation.keys.objects.0.radius.0.0: expected an integer, got 1.5"},
    {R"({"frames": 4, "keys": {"objects.0.radius": [[-1, 1]]}})",
     "animation.keys.objects.0.radius.0.0: must be in [0, 1000000], got -1"},
    {R"({"frames": 4, "keys": {"objects.0.radius": [["0", 1]]}})",
     "animation.keys.objects.0.radius.0.0: expected an integer"},
    // Keyframe values.
    {R"({"frames": 4, "keys": {"objects.0.radius": [[0, 1], [2, [1, 2]]]}})",
     "animation.keys.objects.0.radius.1.1: every keyframe of objects.0.radius must have a value "
     "of the same shape as the first (a number), got [1,2]"},
    {R"({"frames": 4, "keys": {"objects.0.center": [[0, [1, 2, 3]], [2, [1, 2]]]}})",
     "animation.keys.objects.0.center.1.1: every keyframe of objects.0.center must have a value "
     "of the same shape as the first (an array of 3 numbers), got [1,2]"},
    {R"({"frames": 4, "keys": {"objects.0.center": [[0, [1, 2]], [2, 3]]}})",
     "animation.keys.objects.0.center.1.1: every keyframe of objects.0.center must have a value "
     "of the same shape as the first (an array of 2 numbers), got 3"},
    {R"({"frames": 4, "keys": {"objects.0.radius": [[0, "big"]]}})",
     "animation.keys.objects.0.radius.0.1: expected a number or an array of numbers, got string "
     "\"big\""},
    {R"({"frames": 4, "keys": {"objects.0.center": [[0, [1, "a", 3]]]}})",
     "animation.keys.objects.0.center.0.1.1: expected a number, got string \"a\""},
    {R"({"frames": 4, "keys": {"objects.0.radius": [[0, true]]}})",
     "animation.keys.objects.0.radius.0.1: expected a number or an array of numbers, got true"},
    {R"({"frames": 4, "keys": {"objects.0.center": [[0, []]]}})",
     "animation.keys.objects.0.center.0.1: expected a number or an array of numbers, got []"},
    {R"({"frames": 4, "keys": {"objects.0.center": [[0, [1, 2, 3, 4]]]}})",
     "animation.keys.objects.0.center at frame 0 = [1, 2, 3, 4]: objects.0.center: expected an "
     "array of 3 numbers"},
    // The shape of keys.
    {R"({"frames": 3, "keys": []})", "animation.keys: expected an object of PATH"},
    {R"({"frames": 3, "keys": {"objects.0.radius": []}})",
     "animation.keys.objects.0.radius: expected an array of [frame, value] keyframes, got []"},
    {R"({"frames": 3, "keys": {"objects.0.radius": 2}})",
     "animation.keys.objects.0.radius: expected an array of [frame, value] keyframes"},
    {R"({"frames": 3, "keys": {"objects.0.radius": [[0]]}})",
     "animation.keys.objects.0.radius.0: expected a keyframe [frame, value], got [0]"},
    {R"({"frames": 3, "keys": {"objects.0.radius": [[0, 1, 2]]}})",
     "animation.keys.objects.0.radius.0: expected a keyframe [frame, value]"},
    {R"({"frames": 3, "keys": {"": [[0, 1]]}})", "animation.keys: empty scene path"},
    // frames, fps, orbit, unknown keys.
    {R"({"frames": 0})", "animation.frames: must be in [1, 1000000], got 0"},
    {R"({"frames": -3})", "animation.frames: must be in [1, 1000000], got -3"},
    {R"({"frames": 2.5})", "animation.frames: expected an integer, got 2.5"},
    {R"({"fps": 24})", "animation.frames: missing"},
    {R"({})", "animation.frames: missing"},
    {R"({"frames": 3, "fps": 0})", "animation.fps: must be in (0, 1000), got 0"},
    {R"({"frames": 3, "fps": -24})", "animation.fps: must be in (0, 1000), got -24"},
    {R"({"frames": 3, "fps": "24"})", "animation.fps: expected a number"},
    {R"({"frames": 3, "orbit": "a"})", "animation.orbit: expected a number"},
    {R"({"frames": 3, "fsp": 24})", "animation.fsp: unknown key (known: frames, fps, keys, orbit)"},
    {R"(3)", "animation: expected an object, got 3"},
    // Valid at frame 0 and at most keyframes, out of range at frame 10 only: every frame is read.
    {R"({"frames": 11, "keys": {"materials.red.n": [[0, 1], [9, 1], [10, -1]]}})",
     "animation.keys.materials.red.n at frame 10 = -1: materials.red.n: must be > 0, got -1"},
    // Falling linearly from 1 to -1: the first frame out of range is named.
    {R"({"frames": 11, "keys": {"materials.red.n": [[0, 1], [10, -1]]}})",
     "animation.keys.materials.red.n at frame 5 = 0: materials.red.n: must be > 0, got 0"},
    // An integer key is whole at its keyframes, not between them.
    {R"({"frames": 3, "keys": {"image.width": [[0, 32], [3, 64]]}})",
     "animation.keys.image.width at frame 1 = 42.666666666666664: image.width: expected an "
     "integer"},
};

INSTANTIATE_TEST_SUITE_P(Messages, BadAnimationTest, ::testing::ValuesIn(kBadAnimations));

TEST(Animation, AKeyframePastTheLastFrameIsOnlyReadUpToIt) {
    // n falls from 1 to −1 over frames 0 … 20, but the frames stop at 9 (n = 0.1): accepted.
    const std::string json = scene_with(R"({"frames": 10, "keys": {
        "materials.red.n": [[0, 1], [20, -1]]}})");
    EXPECT_NO_THROW(parse(json));
    EXPECT_NEAR(material(frame_of(json, 9), "red").n, 0.1f, 1e-6f);
}

TEST(Animation, AnErrorBetweenKeyframesIsFoundAtLoad) {
    // The camera reaches look_at exactly at frame 5, between keyframes 0 and 10 that are both
    // fine: the loader refuses position == look_at, and parse_scene checks every frame.
    const std::string json = R"({
      "camera": {"projection": "perspective", "position": [0, 0, -5], "look_at": [0, 0, 0]},
      "objects": [{"type": "sphere"}],
      "animation": {"frames": 11, "keys": {"camera.position": [[0, [0, 0, -5]], [10, [0, 0, 5]]]}}
    })";
    for (int f : {0, 4, 6, 10}) EXPECT_NO_THROW(frame_of(json, f)) << f;
    try {
        frame_of(json, 5);
        FAIL() << "frame 5 has the camera at look_at";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()),
                  "scenes/a.json: animation.keys.camera.position at frame 5 = [0, 0, 0]: "
                  "camera.look_at: must differ from camera.position, got [0, 0, 0] for both");
    }
    try {
        parse(json);
        FAIL() << "parse_scene must check every frame";
    } catch (const InputError& e) {
        EXPECT_THAT(e.what(), HasSubstr("animation.keys.camera.position at frame 5 = [0, 0, 0]"));
    }
    // Five frames stop before it: accepted.
    EXPECT_NO_THROW(parse(json, sets({"animation.frames=5"})));
}

TEST(Animation, ABadSetOnTheAnimationIsTheSetsFault) {
    try {
        parse(scene_with(R"({"frames": 3})"), sets({"animation.fps=0"}));
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()), "--set animation.fps=0: must be in (0, 1000), got 0");
    }
}

}  // namespace
}  // namespace luz
