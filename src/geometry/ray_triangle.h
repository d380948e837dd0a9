// The watertight ray–triangle test of Woop, Benthin and Wald (JCGT 2013), shared by triangle and
// mesh shapes and the scene queries' BVH leaves.
#pragma once

#include "geometry/hit.h"
#include "geometry/mesh.h"
#include "math/ray.h"

namespace luz {

/// A ray prepared once for the watertight ray–triangle test: the dominant axis kz of the
/// direction, and the shear that maps the ray onto +z.
struct WatertightRay {
    Vec3 origin;
    int kx = 0, ky = 1, kz = 2;
    float Sx = 0, Sy = 0, Sz = 1;
};
/// Prepares ray r (any non-zero direction) for intersect_triangle().
WatertightRay prepare_watertight(const Ray& r);

/// Watertight ray–triangle test: hit in (t_min, t_max) at t with barycentrics b1, b2 of p1,
/// p2. Rays through an edge or vertex shared by several triangles (same float vertices) hit
/// at least one of them. Both sides count.
bool intersect_triangle(const WatertightRay& r, const Vec3& p0, const Vec3& p1, const Vec3& p2,
                        float t_min, float t_max, float& t, float& b1, float& b2);

/// The nearest hit among all triangles of `mesh` (in index order; ties keep the lowest index):
/// hit.part = the triangle, hit.u, hit.v its barycentrics. hit.shape is left to the caller.
bool intersect_mesh(const Mesh& mesh, const WatertightRay& w, float t_min, float t_max, Hit& hit);

}  // namespace luz
