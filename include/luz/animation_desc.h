// AnimationDesc: the `animation` key (docs/SCENES.md#scene-files) as plain structs: keyframed
// values on scene paths, interpolated linearly and held outside the keys, and a turntable orbit of
// the camera.
#pragma once

#include <string>
#include <vector>

namespace luz {

/// One animated scene path: its keyframes, in strictly increasing frame order.
struct AnimationKey {
    std::string path;                         ///< dotted scene path, as for --set
    bool array = false;                       ///< values are arrays of numbers (else numbers)
    std::vector<int> frames;                  ///< keyframe numbers, strictly increasing
    std::vector<std::vector<double>> values;  ///< one per keyframe, all of the same length
};

struct AnimationDesc {
    int frames = 0;  ///< N: frames 0 … N−1; 0 means the scene has no animation
    double fps = 24;
    std::vector<AnimationKey> keys;
    double orbit = 0;  ///< degrees the camera turns about look_at around up over N frames
};

}  // namespace luz
