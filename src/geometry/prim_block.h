// PrimBlock: four primitives of the scene's BVH side by side (a leaf is one or more blocks), and
// the watertight ray–triangle test (ray_triangle.h) of one ray against a block's four triangles
// at once, with intersect_triangle()'s arithmetic lane for lane: the same hits, the same bits.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>

#include "geometry/ray_cylinder.h"
#include "geometry/ray_triangle.h"
#include "geometry/sphere_group.h"
#include "math/lane4.h"

namespace luz {

/// Slots 4b … 4b+3 of the scene's BVH: in lane k a bounded shape (triangle[k] = kNotTriangle),
/// a sphere in world form (triangle[k] = kSphere: centre v[0][axis][k], radius · radius
/// v[1][0][k], radius v[1][1][k]), an open cylinder in world form (triangle[k] = kCylinder:
/// base v[0][axis][k], unit axis v[1][axis][k], radius · radius v[2][0][k], height v[2][1][k]),
/// another shape around an axis (triangle[k] = kAroundAxis: see axis_lanes_missed()) or one
/// triangle of a mesh shape with its world vertices, by
/// corner and axis (v[corner][axis][k]), so that one load gives an axis of a corner for all
/// four. Lanes past a leaf's end are padding (kPadding: no shape, NaN vertices) that no
/// traversal offers.
struct alignas(16) PrimBlock {
    static constexpr int kLanes = 4;
    static constexpr uint32_t kNotTriangle = 0xFFFFFFFFu;
    static constexpr uint32_t kPadding = 0xFFFFFFFEu;  ///< shape of an unused lane
    static constexpr uint32_t kSphere = 0xFFFFFFFDu;   ///< `triangle` of a world-form sphere
    /// `triangle` of a shape within distance R of a line (cylinder, cone: axis_lanes_missed()).
    static constexpr uint32_t kAroundAxis = 0xFFFFFFFCu;
    /// `triangle` of an open cylinder in world form (tested as cylinder_lanes_roots() does).
    static constexpr uint32_t kCylinder = 0xFFFFFFFBu;

    float v[3][3][kLanes];
    uint32_t shape[kLanes];
    uint32_t triangle[kLanes];

    Vec3 corner(int c, int k) const { return {v[c][0][k], v[c][1][k], v[c][2][k]}; }
    /// Lanes holding triangles (bit k for lane k): a triangle number is below 2³¹
    /// (build_bvh() checks), the markers above have the top bit set, so the lanes are those
    /// that are not negative as signed integers — one comparison.
    unsigned triangle_lanes() const { return lane_bits(triangles() >= lane4i(0)); }
    /// Lanes holding shapes around an axis (pre-tested by axis_lanes_missed()).
    unsigned axis_lanes() const { return lane_bits(triangles() == lane4i(kAroundAxis)); }
    /// Lanes holding world-form spheres.
    unsigned sphere_lanes() const { return lane_bits(triangles() == lane4i(kSphere)); }
    /// Lanes holding open cylinders in world form.
    unsigned cylinder_lanes() const { return lane_bits(triangles() == lane4i(kCylinder)); }
    /// The cylinder lanes `used` as cylinder_lanes_roots() takes them.
    CylinderLanes cylinders(unsigned used) const {
        return {v[0][0], v[0][1], v[0][2], v[1][0], v[1][1], v[1][2], v[2][0], v[2][1], used};
    }
    /// The sphere lanes `used` as sphere_lanes_roots() takes them.
    SphereLanes spheres(unsigned used) const {
        return {v[0][0], v[0][1], v[0][2], v[1][0], v[1][1], used};
    }

  private:
    static Lane4i lane4i(uint32_t x) {
        const int32_t i = static_cast<int32_t>(x);
        return Lane4i{i, i, i, i};
    }
    Lane4i triangles() const {
        Lane4i t;
        std::memcpy(&t, triangle, sizeof t);
        return t;
    }
};
static_assert(sizeof(PrimBlock) == 176);

/// intersect_triangle(r, …, t_min, t_max) for the four lanes of b at once, up to the decision:
/// the lanes that hit at t with barycentrics b1, b2; in `scalar` the lanes whose edge functions
/// need intersect_triangle()'s double path (to be tested one by one). Lanes that hold no
/// triangle give garbage: mask them.
inline unsigned intersect_triangles4(const WatertightRay& r, const PrimBlock& b, float t_min,
                                     float t_max, Lane4f& t, Lane4f& b1, Lane4f& b2,
                                     unsigned& scalar) {
    const auto axis = [&](int corner, int a) {
        Lane4f x;
        std::memcpy(&x, b.v[corner][a], sizeof x);
        return x;
    };
    const Lane4f x[3] = {axis(0, r.kx), axis(1, r.kx), axis(2, r.kx)};
    const Lane4f y[3] = {axis(0, r.ky), axis(1, r.ky), axis(2, r.ky)};
    const Lane4f z[3] = {axis(0, r.kz), axis(1, r.kz), axis(2, r.kz)};
    Lane4i defer;
    const Lane4i hit = intersect_triangle_lanes(x, y, z, lanes4(r.ox), lanes4(r.oy), lanes4(r.oz),
                                                lanes4(r.Sx), lanes4(r.Sy), lanes4(r.Sz),
                                                lanes4(t_min), lanes4(t_max), t, b1, b2, defer);
    scalar = lane_bits(defer);
    return lane_bits(hit) & ~scalar;
}

/// The lanes `lanes` (axis lanes of b) whose shape the line of r surely misses. Lane k holds a
/// shape every point of which lies within R of the line B + s·W (a cylinder or cone of any
/// transform: R² = max(|U|², |V|²) + |U·V| bounds |c·U + s·V|² on the unit disc): B in v[0][·][k],
/// W in v[1][·][k], R_t² ≥ R²·(1 + 2⁻⁸) in v[2][0][k], a slack factor κ in v[2][1][k] and |B|₁ +
/// R_t in v[2][2][k]. The line of r misses when its distance to the axis line,
/// |(o − B)·n| / |n| with n = d × W, exceeds R: tested as (|q| − σ)² > R_t²·|n|², q = (o − B)·n,
/// σ = κ·|d|₁·(|o|₁ + |B|₁ + R_t), far above the float rounding of q and n here and of the
/// shape's own exact test (its ray carried to object space): a lane rejected here is one the
/// exact test misses, so results never change — only the exact tests are spared. NaN never
/// rejects.
[[gnu::always_inline]] inline unsigned axis_lanes_missed(const PrimBlock& b, unsigned lanes,
                                                         const Ray& r) {
    const auto row = [&](int c, int a) {
        Lane4f x;
        std::memcpy(&x, b.v[c][a], sizeof x);
        return x;
    };
    const Lane4f obx = lanes4(r.origin.x) - row(0, 0), oby = lanes4(r.origin.y) - row(0, 1),
                 obz = lanes4(r.origin.z) - row(0, 2);
    const Lane4f wx = row(1, 0), wy = row(1, 1), wz = row(1, 2);
    const Lane4f dx = lanes4(r.direction.x), dy = lanes4(r.direction.y), dz = lanes4(r.direction.z);
    const Lane4f nx = dy * wz - dz * wy, ny = dz * wx - dx * wz, nz = dx * wy - dy * wx;
    const Lane4f q = obx * nx + oby * ny + obz * nz;
    const Lane4f nn = nx * nx + ny * ny + nz * nz;
    const float d1 = std::fabs(r.direction.x) + std::fabs(r.direction.y) + std::fabs(r.direction.z);
    const float o1 = std::fabs(r.origin.x) + std::fabs(r.origin.y) + std::fabs(r.origin.z);
    const Lane4f slack = row(2, 1) * lanes4(d1) * (lanes4(o1) + row(2, 2));
    const Lane4f aq = q < 0 ? -q : q;
    const Lane4f m = aq - slack;
    return lane_bits((m > 0) & (m * m > row(2, 0) * nn)) & lanes;
}

}  // namespace luz
