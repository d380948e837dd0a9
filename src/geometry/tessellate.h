// Tessellation of shapes into triangles with analytic normals, for the zbuffer pipeline: each
// shape's in shapes/<name>.h, dispatched by shapes.cpp.
#pragma once

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

/// Area of the shape's surface as the tessellation would approximate it, in world space,
/// for shapes without a transform's non-uniform scaling (tests compare against it).
double analytic_area(const Shape& s);

}  // namespace luz
