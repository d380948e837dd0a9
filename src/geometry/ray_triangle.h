// The watertight ray–triangle test of Woop, Benthin and Wald (JCGT 2013), shared by triangle and
// mesh shapes and the scene queries' BVH leaves. Inlined: it is the inner loop of every mesh.
#pragma once

#include <cmath>
#include <type_traits>
#include <utility>

#include "geometry/hit.h"
#include "geometry/mesh.h"
#include "math/lane4.h"
#include "math/lane8.h"
#include "math/ray.h"

// intersect_triangle_lanes() takes and returns lane vectors by value between inline functions,
// eight wide even where the build has no AVX (see math/lane8.h): no ABI is crossed.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace luz {

/// A ray prepared once for the watertight ray–triangle test: the dominant axis kz of the
/// direction, the shear that maps the ray onto +z, and the origin's components in that order.
struct WatertightRay {
    Vec3 origin;
    int kx = 0, ky = 1, kz = 2;
    float Sx = 0, Sy = 0, Sz = 1;
    float ox = 0, oy = 0, oz = 0;  ///< origin[kx], origin[ky], origin[kz]
};
namespace watertight_detail {

static_assert(std::is_standard_layout_v<Vec3> && sizeof(Vec3) == 3 * sizeof(float));
/// Component k of v by one indexed load (Vec3::operator[] chooses by comparisons).
inline float at(const Vec3& v, int k) { return reinterpret_cast<const float*>(&v)[k]; }

/// The three edge functions again in double, for when one of them is 0 in float.
void edges_in_double(float Ax, float Ay, float Bx, float By, float Cx, float Cy, float& U, float& V,
                     float& W);

}  // namespace watertight_detail

/// Prepares ray r (any non-zero direction) for intersect_triangle(). Inlined, with indexed
/// loads, no branches and one division: every ray of a mesh starts here. (The shear S need not
/// be d's ratios correctly rounded: each ray's tests share its S, which is all watertightness
/// asks of it.)
[[gnu::always_inline]] inline WatertightRay prepare_watertight(const Ray& r) {
    using watertight_detail::at;
    WatertightRay w;
    w.origin = r.origin;
    const float ax = std::fabs(r.direction.x), ay = std::fabs(r.direction.y),
                az = std::fabs(r.direction.z);
    // kz: x if it beats y and z, else y if it beats z, else z; kx, ky the next two in turn,
    // swapped when d_z < 0 (keeps the winding's sign). In arithmetic: incoherent rays would
    // mispredict branches here.
    const int xy = ax > ay, xz = ax > az, yz = ay > az;
    w.kz = (1 - (xy & xz)) * (2 - yz);  // (x beating y and z with y beating z gives 0 anyway)
    const int next = w.kz == 2 ? 0 : w.kz + 1;
    const int after = next == 2 ? 0 : next + 1;
    const float dz = at(r.direction, w.kz);
    const int flip = -static_cast<int>(dz < 0);  // all ones when d_z < 0
    w.kx = next ^ ((next ^ after) & flip);
    w.ky = after ^ ((next ^ after) & flip);
    w.Sz = 1.0f / dz;
    w.Sx = at(r.direction, w.kx) * w.Sz;
    w.Sy = at(r.direction, w.ky) * w.Sz;
    w.ox = at(r.origin, w.kx);
    w.oy = at(r.origin, w.ky);
    w.oz = at(r.origin, w.kz);
    return w;
}

/// Watertight ray–triangle test: hit in (t_min, t_max) at t with barycentrics b1, b2 of p1,
/// p2. Rays through an edge or vertex shared by several triangles (same float vertices) hit
/// at least one of them. Both sides count.
inline bool intersect_triangle(const WatertightRay& r, const Vec3& p0, const Vec3& p1,
                               const Vec3& p2, float t_min, float t_max, float& t, float& b1,
                               float& b2) {
    using watertight_detail::at;
    // vertices relative to the origin (A = p0 − origin …), sheared so that the ray runs along +z
    const float Az = at(p0, r.kz) - r.oz, Bz = at(p1, r.kz) - r.oz, Cz = at(p2, r.kz) - r.oz;
    const float Ax = (at(p0, r.kx) - r.ox) - r.Sx * Az, Ay = (at(p0, r.ky) - r.oy) - r.Sy * Az;
    const float Bx = (at(p1, r.kx) - r.ox) - r.Sx * Bz, By = (at(p1, r.ky) - r.oy) - r.Sy * Bz;
    const float Cx = (at(p2, r.kx) - r.ox) - r.Sx * Cz, Cy = (at(p2, r.ky) - r.oy) - r.Sy * Cz;
    // scaled barycentrics: 2D edge functions; exact in double when one is zero in float
    float U = Cx * By - Cy * Bx, V = Ax * Cy - Ay * Cx, W = Bx * Ay - By * Ax;
    if (U == 0.0f || V == 0.0f || W == 0.0f)
        watertight_detail::edges_in_double(Ax, Ay, Bx, By, Cx, Cy, U, V, W);
    if ((U < 0 || V < 0 || W < 0) && (U > 0 || V > 0 || W > 0)) return false;
    const float det = U + V + W;
    if (det == 0.0f) return false;
    const float T = U * (r.Sz * Az) + V * (r.Sz * Bz) + W * (r.Sz * Cz);
    const float inv_det = 1.0f / det;
    const float tt = T * inv_det;
    if (!(tt > t_min && tt < t_max)) return false;
    t = tt;
    b1 = V * inv_det;
    b2 = W * inv_det;
    return true;
}

/// intersect_triangle() on lanes of type F (a GCC float vector; I its mask type), its arithmetic
/// lane for lane, up to the decision: x[c], y[c], z[c] are corner c's coordinates on the ray's
/// axes kx, ky, kz; o* and S* the ray's origin and shear on them. Returns the lanes that hit in
/// (t_min, t_max) at t with barycentrics b1, b2; `scalar` holds the lanes whose edge functions
/// need the double path (to be tested by intersect_triangle(); their hit lanes mean nothing).
template <class F, class I>
inline I intersect_triangle_lanes(const F (&x)[3], const F (&y)[3], const F (&z)[3], F ox, F oy,
                                  F oz, F Sx, F Sy, F Sz, F t_min, F t_max, F& t, F& b1, F& b2,
                                  I& scalar) {
    const F Az = z[0] - oz, Bz = z[1] - oz, Cz = z[2] - oz;
    const F Ax = (x[0] - ox) - Sx * Az, Ay = (y[0] - oy) - Sy * Az;
    const F Bx = (x[1] - ox) - Sx * Bz, By = (y[1] - oy) - Sy * Bz;
    const F Cx = (x[2] - ox) - Sx * Cz, Cy = (y[2] - oy) - Sy * Cz;
    const F U = Cx * By - Cy * Bx, V = Ax * Cy - Ay * Cx, W = Bx * Ay - By * Ax;
    const F zero = F{};
    scalar = lane_eq(U, zero) | lane_eq(V, zero) | lane_eq(W, zero);
    const I outside = (lane_lt(U, zero) | lane_lt(V, zero) | lane_lt(W, zero)) &
                      (lane_gt(U, zero) | lane_gt(V, zero) | lane_gt(W, zero));
    const F det = U + V + W;
    const F T = U * (Sz * Az) + V * (Sz * Bz) + W * (Sz * Cz);
    const F inv_det = (zero + 1.0f) / det;
    t = T * inv_det;
    b1 = V * inv_det;
    b2 = W * inv_det;
    return ~outside & lane_ne(det, zero) & lane_gt(t, t_min) & lane_lt(t, t_max);
}

/// The nearest hit among all triangles of `mesh` (in index order; ties keep the lowest index):
/// hit.part = the triangle, hit.u, hit.v its barycentrics. hit.shape is left to the caller.
bool intersect_mesh(const Mesh& mesh, const WatertightRay& w, float t_min, float t_max, Hit& hit);

}  // namespace luz
