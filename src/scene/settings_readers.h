// The scene loader's readers of the `image`, `camera`, `render` and `lights` sections.
#pragma once

#include "scene/json_text.h"
#include "scene/scene_desc.h"

namespace luz::loader {

/// `image`: size (at most kMaxPixels in all), background, encoding. Throws KeyError.
void read_image(const Json& j, ImageDesc& image);

/// `camera` (nullptr when absent), then the check that its basis (docs/SCENES.md#geometry) exists.
void read_camera(const Json* j, CameraDesc& camera);

/// `render`, with `antialias`.
/// The `render` section: settings into `render`, tessellation and accel into `geometry`.
void read_render(const Json& j, RenderDesc& render, GeometryDesc& geometry);

/// `lights` (nullptr when absent). Without lights, one white light at the camera's upper left;
/// needs scene.camera, scene.render.model, scene.attenuation_k and scene.attenuation read first.
void read_lights(const Json* j, SceneDesc& scene);

}  // namespace luz::loader
