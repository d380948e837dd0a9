// Wavefront OBJ and MTL input (docs/SCENES.md#scene-files `mesh`): tinyobjloader parses,
// scene/triangulate.h cuts polygons into triangles, after a light pass of our own that checks every
// number and index and names FILE:LINE on bad input.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "scene/input_error.h"
#include "scene/mesh_data.h"
#include "scene/text_files.h"

namespace luz {

/// Parses the OBJ text of `file` (`file` labels messages and locates MTL files: `mtllib` names
/// are relative to its folder; `read` reads them). Polygons are triangulated; `v`, `vn`, `f`,
/// `usemtl` and `mtllib` are used, other statements ignored. With `with_materials` false the MTL
/// files are not read and every face has material −1.
///
/// MTL mapping (docs/SCENES.md#scene-files): Ka, Kd, Ks → ka, kd, ks (clamped to [0, 1]); Ns → n
/// (Ns ≤ 0 → 1); Ni → ior (below 1 → 1); d → transparency = 1 − d, or Tr → transparency = Tr (d
/// wins); illum 3–7 → reflection = mean of Ks. Keys a material omits keep the default material's.
///
/// Throws InputError "FILE:LINE: what" on a malformed number, a non-finite coordinate, a bad
/// or out-of-range index, or a face with fewer than 3 vertices (MTL errors name the MTL file).
/// A missing MTL file, an unknown `usemtl` name, a clamped MTL value and a file without faces
/// are warnings ("FILE:LINE: what"), appended to `warnings`.
MeshData parse_obj(std::string_view text, const std::string& file, bool with_materials,
                   const TextReader& read, std::vector<std::string>& warnings);

/// Reads and parses the OBJ file at `path` (and its MTL files) from disk. A missing or
/// unreadable OBJ file throws InputError "PATH: cannot read: reason".
MeshData load_obj(const std::string& path, bool with_materials, std::vector<std::string>& warnings);

}  // namespace luz
