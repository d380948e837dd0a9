// The triangles standing for an unbounded plane in the zbuffer: a grid far larger than the scene,
// centred under the camera, that the rasterizer clips to the view.
#pragma once

#include "geometry/scene.h"
#include "geometry/shape.h"
#include "geometry/triangle_mesh.h"
#include "scene/scene_desc.h"

namespace luz {

/// Appends to `mesh` plane `plane` as a square far larger than `scene` (its bounded shapes and
/// `camera`), centred at the camera's foot on the plane, made of a grid whose cells double in
/// size away from the centre: every point is interpolated from nearby vertices, so positions
/// (and checker cells) stay precise. Vertex normals are the plane's normal.
void append_plane_grid(const BuiltScene& scene, const CameraDesc& camera, const Shape& plane,
                       TriangleMesh& mesh);

}  // namespace luz
