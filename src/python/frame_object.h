// luz.Frame: what a render made, owned by Python; its image and per-term images are numpy
// views over the frame's own memory, each keeping the frame alive.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <memory>
#include <string>

#include "luz/luz.h"
#include "python/scene_handle.h"

namespace luz::python {

struct FrameObject {
    Frame frame;
    SceneRef scene;  ///< the scene as rendered (its settings: encoding, names, the stats' keys)
};

/// `image` (float RGB, row 0 on top) as a float32 (h, w, 3) array over its pixels, or, with
/// `scalar`, its first channel as (h, w) (strides w·12, 12): no copy; `owner` (the Python
/// Frame) is kept alive by the array.
pybind11::array image_view(const Image& image, bool scalar, pybind11::handle owner);

/// The frame's statistics: the --stats JSON as a dict.
pybind11::dict frame_stats(const FrameObject& f);

/// Writes the image and its per-term images to `path` as `luz render -o PATH` does
/// (format by extension, atomically). Throws SceneError for a bad path, OSError on failure.
void save_frame(const FrameObject& f, const std::string& path);

/// The PNG file `luz render -o X.png` writes for this frame, as bytes.
pybind11::bytes frame_png(const FrameObject& f);

}  // namespace luz::python
