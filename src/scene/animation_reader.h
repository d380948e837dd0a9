// Reads the `animation` key (docs/SCENES.md#scene-files) into an AnimationDesc; errors name its key
// path.
#pragma once

#include "scene/animation_desc.h"
#include "scene/json_text.h"

namespace luz::loader {

/// `j` is the document's `animation` value. Checks its own shape: frames ≥ 1, fps > 0, keys
/// an object of PATH: [[frame, value], …] with whole frames ≥ 0 strictly increasing and values
/// all numbers or all arrays of one length, orbit finite. Whether each PATH is a scene key with
/// such values is checked by reading the scene at every frame. Throws KeyError.
AnimationDesc read_animation(const Json& j);

}  // namespace luz::loader
