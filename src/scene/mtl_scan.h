// The MTL files of an OBJ (docs/SCENES.md#scene-files `mesh`): a strict reading of their materials,
// mapped to luz's constants, in the order tinyobjloader lists them.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "scene/material.h"

namespace luz {

/// The MTL materials of `text` in the order tinyobjloader's LoadMtl lists them (a material is
/// listed at the next `newmtl` if it has a name, and the last one always), mapped per
/// docs/SCENES.md#scene-files; names get `prefix`. Values are read here, strictly, rather than from
/// tinyobjloader, whose number parser falls back to 0 silently and reads "Kd 0.5" as (0.5, 0, 0).
/// Throws InputError "FILE:LINE: what"; a constant clamped to [0, 1] is a warning appended to
/// `warnings`.
std::vector<Material> scan_mtl(std::string_view text, const std::string& file,
                               const std::string& prefix, std::vector<std::string>& warnings);

}  // namespace luz
