// MeshData: the triangles of a Wavefront OBJ file as the file gives them (object space), with
// its MTL materials; the geometry layer turns it into a world-space Mesh (geometry/mesh.h).
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "math/vec3.h"
#include "scene/material.h"

namespace luz {

struct MeshData {
    std::string file;                 ///< the OBJ file as the user named it (for messages)
    std::vector<Vec3> positions;      ///< `v` statements, in file order
    std::vector<Vec3> normals;        ///< `vn` statements, in file order (any length)
    std::vector<uint32_t> position;   ///< 3 per triangle: indices into positions
    std::vector<int32_t> normal;      ///< 3 per triangle: indices into normals, −1 when absent
    std::vector<int32_t> material;    ///< per triangle: index into materials, −1 when none
    std::vector<Material> materials;  ///< the MTL materials faces use (names "file.obj:name")

    size_t triangle_count() const { return position.size() / 3; }
};

/// Meshes already read, by (file as named, with its MTL materials): the frames of an animation
/// read each OBJ file once (scene_loader.h).
using MeshCache = std::map<std::pair<std::string, bool>, std::shared_ptr<const MeshData>>;

}  // namespace luz
