// Triangulation of an OBJ face: a simple polygon, convex or not (the gears of the Standard
// Procedural Databases are concave 144-gons), in time near linear in its corners.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "math/vec3.h"

namespace luz {

/// Appends to `out` the triangles of the polygon whose corners are `corners`, in order, each as
/// three indices into `corners` in the polygon's own winding. A triangle is itself; a quad is
/// split along its shorter diagonal (as tinyobjloader splits it); a larger polygon is projected
/// on the plane its Newell normal is most along and cut by ear clipping, the reflex corners in
/// a grid so that each ear is checked against the few near it. Corners that add no area
/// (repeated, or in line with their neighbours) are dropped, so a polygon without area gives no
/// triangle. A polygon that crosses itself still gives triangles (not an exact cover).
void triangulate_polygon(const std::vector<Vec3>& corners,
                         std::vector<std::array<uint32_t, 3>>& out);

}  // namespace luz
