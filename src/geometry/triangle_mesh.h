// TriangleMesh: shared vertex and index arrays; a triangle is three indices.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "math/vec3.h"

namespace luz {

struct TriangleMesh {
    std::vector<Vec3> positions;    ///< world space
    std::vector<Vec3> normals;      ///< unit, outward, one per position
    std::vector<uint32_t> indices;  ///< 3 per triangle, counter-clockwise seen from outside

    size_t triangle_count() const { return indices.size() / 3; }
    /// Room for `vertices` more vertices and `more_indices` more indices, growing at least
    /// twofold: shapes appended one after another each reserving exactly what they add would
    /// copy all the shapes before them every time (3000 spheres: minutes).
    void reserve_more(size_t vertices, size_t more_indices) {
        grow(positions, vertices);
        grow(normals, vertices);
        grow(indices, more_indices);
    }
    void clear() {
        positions.clear();
        normals.clear();
        indices.clear();
    }

  private:
    template <typename T>
    static void grow(std::vector<T>& v, size_t more) {
        if (v.size() + more > v.capacity()) v.reserve(std::max(v.size() + more, 2 * v.capacity()));
    }
};

}  // namespace luz
