// Camera controls of the viewer: orbit about look_at, pan in the view plane, zoom.
#pragma once

#include "luz/luz.h"

namespace luz {

/// Orbits the camera about look_at: `yaw` degrees about `up`, `pitch` degrees about the
/// camera's horizontal axis (kept short of the poles).
void orbit_camera(CameraDesc& c, float yaw, float pitch);

/// Moves position and look_at together by (dx, dy) image heights along the camera's u, v.
void pan_camera(CameraDesc& c, float dx, float dy);

/// Zooms by `factor` (< 1 closer): the orthographic view_height, or the perspective distance
/// to look_at.
void zoom_camera(CameraDesc& c, float factor);

}  // namespace luz
