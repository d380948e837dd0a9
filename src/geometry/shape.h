// Shape: one object of the scene in its canonical object space, placed by a transform. Each
// type's geometry is in shapes/<name>.h; shapes.h dispatches to it (intersect, count_crossings,
// surface_at; bounds and make_shape here, tessellate in tessellate.h).
#pragma once

#include <memory>
#include <vector>

#include "geometry/mesh.h"
#include "math/bounds.h"
#include "math/transform.h"
#include "scene/scene_desc.h"

namespace luz {

/// Canonical object spaces (world = transform.world_from_object · object):
/// - sphere:   the unit sphere at the origin;
/// - box:      the axis-aligned box [lo, hi];
/// - cylinder: radius 1 around +z, z ∈ [0, 1], `caps` closes z = 0 and z = 1;
/// - cone:     radius 1 − (1 − apex)·z around +z, z ∈ [0, 1] (radius `apex` at z = 1: 0 is a
///             full cone, > 0 a frustum), `caps` closes z = 0 and, for a frustum, z = 1;
/// - torus:    major radius 1 around +z in the z = 0 plane, minor radius `minor` (< 1);
/// - plane:    z = 0, outward normal +z, unbounded;
/// - triangle: `vertices` as the keys give them; two-sided.
/// - mesh:     `mesh`, already in world space (identity transform); two-sided.
struct Shape {
    ShapeType type = ShapeType::sphere;
    int material = 0;                  ///< index into SceneDesc::materials
    int object = 0;                    ///< index into SceneDesc::objects
    Transform transform;               ///< user transform · placement of the canonical shape
    bool caps = false;                 ///< cylinder: both ends; cone: the base (frustum: both)
    float apex = 0;                    ///< cone: apex_radius / radius, in [0, 1)
    float minor = 0.25f;               ///< torus: minor_radius / major_radius
    Vec3 lo, hi;                       ///< box corners in object space
    Vec3 vertices[3];                  ///< triangle vertices in object space
    std::shared_ptr<const Mesh> mesh;  ///< mesh: its triangles (shared by copies of the shape)
    bool bounded = true;               ///< finite (shapes::<name>::bounded; planes are not)
    /// In the scene's BVH as pieces along its axis, in several leaves (build_bvh(): a long
    /// slanted cylinder or cone): a shadow ray counts its crossings once (query::Crossings).
    bool split = false;

    /// World-space form, for the ray tracer's fast path (shapes/sphere.h, shapes/plane.h,
    /// shapes/cylinder.h): set for every plane (n·p = offset, n the unit outward normal), for a
    /// sphere whose transform is a similarity (|p − centre| = radius) and for an open cylinder
    /// that stays round (base `centre`, unit axis `normal`, `radius`, height `offset`); other
    /// shapes are hit in object space.
    bool world_form = false;
    Vec3 centre, normal;  ///< sphere: centre; plane: unit normal n; cylinder: base, unit axis
    float radius = 0;     ///< sphere, cylinder: radius
    float offset = 0;     ///< plane: n·p for its points p; cylinder: height
};

/// The runtime shape of an object description (validated: non-degenerate): its type's
/// shapes::<name>::place (shapes.cpp).
Shape make_shape(const ObjectDesc& o, int object_index);

/// World-space bounds; an unbounded plane gives infinite bounds (shapes.cpp).
Bounds3 bounds(const Shape& s);

/// Whether the shape is finite (everything but the plane).
inline bool is_bounded(const Shape& s) { return s.bounded; }

}  // namespace luz
