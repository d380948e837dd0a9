// PrimBlock: four primitives of the scene's BVH side by side (a leaf is one or more blocks), and
// the watertight ray–triangle test (ray_triangle.h) of one ray against a block's four triangles
// at once, with intersect_triangle()'s arithmetic lane for lane: the same hits, the same bits.
#pragma once

#include <cstdint>
#include <cstring>

#include "geometry/ray_triangle.h"
#include "math/lane4.h"

namespace luz {

/// Slots 4b … 4b+3 of the scene's BVH: in lane k a bounded shape (triangle[k] = kNotTriangle)
/// or one triangle of a mesh shape with its world vertices, by corner and axis
/// (v[corner][axis][k]), so that one load gives an axis of a corner for all four. Lanes past a
/// leaf's end are padding (kPadding: no shape, NaN vertices) that no traversal offers.
struct alignas(16) PrimBlock {
    static constexpr int kLanes = 4;
    static constexpr uint32_t kNotTriangle = 0xFFFFFFFFu;
    static constexpr uint32_t kPadding = 0xFFFFFFFEu;  ///< shape of an unused lane

    float v[3][3][kLanes];
    uint32_t shape[kLanes];
    uint32_t triangle[kLanes];

    Vec3 corner(int c, int k) const { return {v[c][0][k], v[c][1][k], v[c][2][k]}; }
    /// Lanes holding triangles (bit k for lane k).
    unsigned triangle_lanes() const {
        Lane4i t;
        std::memcpy(&t, triangle, sizeof t);
        return lane_bits4(t != Lane4i{-1, -1, -1, -1});
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
    scalar = lane_bits4(defer);
    return lane_bits4(hit) & ~scalar;
}

}  // namespace luz
