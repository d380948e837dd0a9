// Tessellation of shapes into triangles with analytic normals, for the zbuffer pipeline: each
// shape's in shapes/<name>.h, dispatched by shapes.cpp.
#pragma once

#include <cstdint>

#include "geometry/shape.h"
#include "geometry/triangle_mesh.h"

namespace luz {

/// Appends the triangles of shape `s` in world space to `out` at tessellation `level`
/// (segments around a full circle; ≥ 3). Normals are the analytic surface normals transformed
/// by the inverse transpose, normalised. Closed shapes come out watertight (every edge shared
/// by exactly two triangles, by position). Planes append nothing (the rasterizer draws them
/// as quads clipped to the view). A mesh appends its own triangles, in order, whatever the
/// level (flat meshes: three vertices per triangle with the face normal).
void tessellate(const Shape& s, int level, TriangleMesh& out);

/// How many triangles tessellate() appends for object `o` at `level` (what each shape's emitter
/// reserves; tests/geometry/tessellate_test.cpp compares): a sphere 2·n·(n/2 − 1), a torus
/// 2·n·(n/2), a cylinder or frustum 2n and n a cap, a cone n and n its cap, a box 12, a triangle
/// 1, a mesh its own, a plane none (n = level, at least 3). For the memory check.
uint64_t tessellated_triangle_count(const ObjectDesc& o, int level);

/// Area of the shape's surface as the tessellation would approximate it, in world space,
/// for shapes without a transform's non-uniform scaling (tests compare against it).
double analytic_area(const Shape& s);

}  // namespace luz
