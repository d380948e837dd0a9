// Mesh: a triangle mesh in world space (docs/SCENES.md#scene-files `mesh`) — shared vertex and
// index arrays, a triangle is an index; built once from the loaded OBJ data with the object's
// transform applied.
#pragma once

#include <cstdint>
#include <vector>

#include "math/bounds.h"
#include "math/vec3.h"
#include "scene/scene_desc.h"

namespace luz {

struct Mesh {
    std::vector<Vec3> positions;     ///< world space
    std::vector<Vec3> normals;       ///< smooth: unit shading normal per vertex; flat: empty
    std::vector<uint32_t> indices;   ///< 3 per triangle, counter-clockwise seen from outside
    std::vector<int32_t> materials;  ///< per triangle: index into SceneDesc::materials
    std::vector<Vec3> face_normals;  ///< per triangle: face_normal(), kept by build_mesh()
    Bounds3 bounds;                  ///< of the vertices triangles use

    size_t triangle_count() const { return indices.size() / 3; }
    bool smooth() const { return !normals.empty(); }
    /// The world-space vertices of triangle t.
    void vertices(size_t t, Vec3& p0, Vec3& p1, Vec3& p2) const {
        p0 = positions[indices[3 * t]];
        p1 = positions[indices[3 * t + 1]];
        p2 = positions[indices[3 * t + 2]];
    }
    /// The unit winding normal (p1 − p0) × (p2 − p0) of triangle t; +z for a zero-area one.
    /// Kept per triangle (build_mesh()): every hit on a mesh needs it.
    const Vec3& face_normal(size_t t) const { return face_normals[t]; }
    /// The unit shading normal at barycentrics (b1, b2) of triangle t: the vertex normals
    /// interpolated (smooth), else the face normal; turned to the face normal's side.
    Vec3 shading_normal(size_t t, float b1, float b2) const {
        return shading_normal(t, b1, b2, face_normal(t));
    }
    /// The same, given triangle t's face normal Ng (face_normal(t)).
    Vec3 shading_normal(size_t t, float b1, float b2, const Vec3& Ng) const;
};

/// The world-space mesh of a mesh object (o.mesh loaded): positions by o.transform, normals by
/// its inverse transpose; a mirroring transform reverses the winding so that faces stay
/// counter-clockwise from outside. Smooth (`smooth`: true): the file's `vn` normals where a
/// face corner gives one, elsewhere the angle-weighted average of the face normals around the
/// vertex (Thürmer and Wüthrich); vertices are shared by every corner with the same position
/// and normal. Flat: no vertex normals (the face normal everywhere). Per-triangle materials:
/// o.mesh_materials of the face's MTL material, else o.material. Throws InputError if a
/// vertex leaves float range under the transform.
Mesh build_mesh(const ObjectDesc& o);

}  // namespace luz
