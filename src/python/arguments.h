// The keyword arguments of luz.render() and luz.ray_tree(), checked: a wrong type raises
// TypeError, a bad value ValueError, each naming the argument; the scene-setting ones become
// the very overrides `luz render`'s options make (option_overrides()).
#pragma once

#include <pybind11/pybind11.h>

#include <optional>
#include <string>
#include <vector>

#include "luz/luz.h"
#include "luz/options.h"

namespace luz::python {

/// pipeline, model, width, height, max_depth, aa, samples, threshold (None: unset) as the
/// CLI's option values: words as they are, integers and numbers as their text.
SceneOptions scene_options(pybind11::handle pipeline, pybind11::handle model,
                           pybind11::handle width, pybind11::handle height,
                           pybind11::handle max_depth, pybind11::handle aa,
                           pybind11::handle samples, pybind11::handle threshold);

/// An int argument (int or anything with __index__, not bool) in [lo, hi].
long long int_argument(pybind11::handle value, const char* name, long long lo, long long hi);

/// The per-term images asked for: None, a str ("diffuse,depth", "all") or an iterable of
/// names. Unknown names raise ValueError listing the valid ones.
std::vector<AovKind> aov_argument(pybind11::handle aov);

/// region=: None (the whole image) or a sequence of four ints (x0, y0, x1, y1), x1 and y1
/// exclusive; checked against the image by check_region_argument() once the scene is known.
std::optional<PixelRect> region_argument(pybind11::handle region);

/// Raises ValueError naming region= when `r` is set and empty or outside `image`.
void check_region_argument(const std::optional<PixelRect>& r, const ImageDesc& image);

/// A path argument (str, bytes or os.PathLike) as a str; one holding a NUL raises ValueError.
std::string path_argument(pybind11::handle path, const char* name);

}  // namespace luz::python
