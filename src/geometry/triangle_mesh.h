// TriangleMesh: shared vertex and index arrays; a triangle is three indices.
#pragma once

#include <cstdint>
#include <vector>

#include "math/vec3.h"

namespace luz {

struct TriangleMesh {
    std::vector<Vec3> positions;    ///< world space
    std::vector<Vec3> normals;      ///< unit, outward, one per position
    std::vector<uint32_t> indices;  ///< 3 per triangle, counter-clockwise seen from outside

    size_t triangle_count() const { return indices.size() / 3; }
    void clear() {
        positions.clear();
        normals.clear();
        indices.clear();
    }
};

}  // namespace luz
