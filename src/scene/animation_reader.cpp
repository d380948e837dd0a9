// The `animation` key (docs/SCENES.md#scene-files): frames, fps, keys {PATH: [[frame, value], …]},
// orbit.
#include "scene/animation_reader.h"

#include "scene/json_readers.h"
#include "scene/limits.h"

namespace luz::loader {
namespace {

/// The most frames an animation may have (about 11.5 hours at 24 fps).
constexpr int kMaxFrames = 1'000'000;

AnimationKey read_key(const std::string& scene_path, const Json& j, const std::string& path) {
    AnimationKey key;
    key.path = scene_path;
    if (!j.is_array() || j.empty()) {
        fail(path, "expected an array of [frame, value] keyframes, got " + describe(j));
    }
    for (std::size_t i = 0; i < j.size(); ++i) {
        const std::string at = join(path, i);
        const Json& kf = j[i];
        if (!kf.is_array() || kf.size() != 2) {
            fail(at, "expected a keyframe [frame, value], got " + describe(kf));
        }
        const int frame = read_int(kf[0], join(at, 0), 0, kMaxFrames);
        if (i > 0 && frame <= key.frames.back()) {
            fail(join(at, 0), "keyframes must be in increasing frame order: frame " +
                                  std::to_string(frame) + " after frame " +
                                  std::to_string(key.frames.back()));
        }
        const Json& v = kf[1];
        std::vector<double> value;
        const bool array = v.is_array();
        if (array) {
            if (v.empty()) fail(join(at, 1), "expected a number or an array of numbers, got []");
            for (std::size_t c = 0; c < v.size(); ++c) {
                value.push_back(read_number(v[c], join(join(at, 1), c)));
            }
        } else if (v.is_number()) {
            value.push_back(read_number(v, join(at, 1)));
        } else {
            fail(join(at, 1), "expected a number or an array of numbers, got " + describe(v));
        }
        if (i > 0 && (array != key.array || value.size() != key.values.back().size())) {
            fail(join(at, 1),
                 "every keyframe of " + scene_path +
                     " must have a value of the same shape as the first (" +
                     (key.array
                          ? "an array of " + std::to_string(key.values.back().size()) + " numbers"
                          : std::string("a number")) +
                     "), got " + describe(v));
        }
        key.array = array;
        key.frames.push_back(frame);
        key.values.push_back(std::move(value));
    }
    return key;
}

}  // namespace

AnimationDesc read_animation(const Json& j) {
    const Section s(j, "animation", {"frames", "fps", "keys", "orbit"}, "animation");
    AnimationDesc a;
    const Json* frames = s.get("frames");
    if (!frames) fail("animation.frames", "missing: the number of frames, e.g. \"frames\": 48");
    a.frames = read_int(*frames, s.key("frames"), 1, kMaxFrames);
    if (const Json* v = s.get("fps")) {
        static constexpr Limit kFps = strictly_between(0, 1000, 1, 120);
        a.fps = read_number(*v, s.key("fps"), kFps);
    }
    if (const Json* v = s.get("orbit")) a.orbit = read_number(*v, s.key("orbit"));
    if (const Json* keys = s.get("keys")) {
        if (!keys->is_object()) {
            fail(s.key("keys"),
                 "expected an object of PATH: [[frame, value], …], got " + describe(*keys));
        }
        for (const auto& item : keys->items()) {
            if (item.key().empty()) fail(s.key("keys"), "empty scene path");
            if (item.key() == "animation" || item.key().rfind("animation.", 0) == 0) {
                fail(join(s.key("keys"), item.key()), "the animation cannot animate itself");
            }
            a.keys.push_back(read_key(item.key(), item.value(), join(s.key("keys"), item.key())));
        }
    }
    return a;
}

}  // namespace luz::loader
