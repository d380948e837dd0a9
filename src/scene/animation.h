// A frame of an animation (docs/SCENES.md#scene-files `animation`): the keyframed values at frame f
// as --set-style overrides of the scene document, and the camera's turntable orbit applied after
// them.
#pragma once

#include <string>
#include <vector>

#include "scene/animation_desc.h"
#include "scene/scene_desc.h"
#include "scene/scene_loader.h"

namespace luz {

/// The value of `key` at frame `f`: linear between keyframes, held before the first and after
/// the last. Exactly a keyframe's value at that keyframe.
std::vector<double> key_value(const AnimationKey& key, int f);

/// One override per key, setting its path to its value at frame `f`; each is named in messages
/// as "LABEL: animation.keys.PATH at frame F =" followed by the value.
std::vector<Override> frame_overrides(const AnimationDesc& a, int f, const std::string& label);

/// Turns `camera.position` about `camera.look_at` around `camera.up` by orbit·f/frames degrees
/// (counter-clockwise seen from where `up` points). No change when orbit is 0.
void apply_orbit(const AnimationDesc& a, int f, CameraDesc& camera);

}  // namespace luz
