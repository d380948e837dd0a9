// The rasterizer's per-triangle kernels (render/raster_kernels.h): one set-up of the edge
// functions, then the reference loop over lattice points or the eight-lane loop over a row.
#include "render/raster_kernels.h"

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <utility>

#include "geometry/ray_packet.h"

namespace luz {

namespace {

/// A triangle's edge functions on a lattice, for both kernels. Edge k is opposite vertex k:
/// E_k(p) = (b − a) × (p − a) for a = v[k+1], b = v[k+2], ≥ 0 inside once the vertices run
/// counter-clockwise on screen (y down); e0 holds E_k − bias_k at lattice point (px0, py0).
struct EdgeSetup {
    bool empty = true;
    bool swapped = false;  ///< vertices 1 and 2 exchanged to make the area positive
    int px0, px1, py0, py1;
    int64_t area;
    int64_t extent_x, extent_y;  ///< the bounding box's size, fixed point
    int64_t ex[3], ey[3], e0[3], bias[3];
    float d[3], iw[3];  ///< depth and 1/w of the set-up vertices
};

EdgeSetup set_up(const RasterTriangle& r, const Lattice& lat) {
    EdgeSetup s;
    int64_t x[3] = {r.x[0], r.x[1], r.x[2]}, y[3] = {r.y[0], r.y[1], r.y[2]};
    int order[3] = {0, 1, 2};
    int64_t area = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
    if (area < 0) {
        std::swap(x[1], x[2]);
        std::swap(y[1], y[2]);
        std::swap(order[1], order[2]);
        area = -area;
        s.swapped = true;
    }
    s.area = area;
    const int64_t step = lat.step;
    // Lattice range of the bounding box.
    const int64_t min_x = std::min({x[0], x[1], x[2]}), max_x = std::max({x[0], x[1], x[2]});
    const int64_t min_y = std::min({y[0], y[1], y[2]}), max_y = std::max({y[0], y[1], y[2]});
    s.extent_x = max_x - min_x;
    s.extent_y = max_y - min_y;
    s.px0 = static_cast<int>(std::max<int64_t>(0, ceil_div(min_x - lat.x0, step)));
    s.px1 = static_cast<int>(std::min<int64_t>(lat.w - 1, floor_div(max_x - lat.x0, step)));
    s.py0 = static_cast<int>(std::max<int64_t>(0, ceil_div(min_y - lat.y0, step)));
    s.py1 = static_cast<int>(std::min<int64_t>(lat.h - 1, floor_div(max_y - lat.y0, step)));
    if (s.px0 > s.px1 || s.py0 > s.py1) return s;
    s.empty = false;

    const int64_t sx = lat.x0 + s.px0 * step, sy = lat.y0 + s.py0 * step;
    for (int k = 0; k < 3; ++k) {
        const int a = (k + 1) % 3, b = (k + 2) % 3;
        const int64_t dx = x[b] - x[a], dy = y[b] - y[a];
        // Inside: E_k = dx·(py − ya) − dy·(px − xa) ≥ 0 (y down, positive area).
        s.ex[k] = -dy * step;  // change per lattice step in x
        s.ey[k] = dx * step;   // change per lattice step in y
        s.e0[k] = dx * (sy - y[a]) - dy * (sx - x[a]);
        // Top-left rule: a lattice point exactly on an edge belongs to the triangle only if the
        // edge is a top edge (horizontal, interior below) or a left edge.
        const bool top = dy == 0 && dx > 0;
        const bool left = dy < 0;
        s.bias[k] = (top || left) ? 0 : 1;
        s.e0[k] -= s.bias[k];
    }
    for (int k = 0; k < 3; ++k) {
        s.d[k] = r.depth[order[k]];
        s.iw[k] = r.inv_w[order[k]];
    }
    return s;
}

/// Barycentrics of the set-up vertices (b0, b1, b2) → of the original triangle: (o1, o2).
inline void original_bary(const EdgeSetup& s, const std::array<Vec3, 3>* clip_bary, float b0,
                          float b1, float b2, float& o1, float& o2) {
    // order = {0, 1, 2}, or {0, 2, 1} when swapped: o[order[k]] = b[k]
    o1 = s.swapped ? b2 : b1;
    o2 = s.swapped ? b1 : b2;
    if (clip_bary) {
        const auto& cb = *clip_bary;
        const Vec3 ob = cb[0] * b0 + cb[1] * o1 + cb[2] * o2;
        o1 = ob.y;
        o2 = ob.z;
    }
}

/// f[k] = {depth[k], triangle, o1[k], o2[k]} for the lanes k where `nearer` is set, f[k] as it
/// was elsewhere: the lanes transposed into eight 16-byte fragments, blended with the eight
/// there, four 32-byte stores.
inline void store_fragments(Fragment* f, Lane8i nearer, Lane8f depth, uint32_t triangle, Lane8f o1,
                            Lane8f o2) {
    static_assert(sizeof(Fragment) == 4 * sizeof(float) && offsetof(Fragment, triangle) == 4 &&
                  offsetof(Fragment, b1) == 8 && offsetof(Fragment, b2) == 12);
    const Lane8f t = (Lane8f)(Lane8i{} + static_cast<int32_t>(triangle));
    // (d0 t d1 t d2 t d3 t), (o1₀ o2₀ o1₁ o2₁ …) and the same of lanes 4 … 7
    const Lane8f dt_lo = __builtin_shufflevector(depth, t, 0, 8, 1, 9, 2, 10, 3, 11);
    const Lane8f o_lo = __builtin_shufflevector(o1, o2, 0, 8, 1, 9, 2, 10, 3, 11);
    const Lane8f dt_hi = __builtin_shufflevector(depth, t, 4, 12, 5, 13, 6, 14, 7, 15);
    const Lane8f o_hi = __builtin_shufflevector(o1, o2, 4, 12, 5, 13, 6, 14, 7, 15);
    const Lane8f fresh[4] = {__builtin_shufflevector(dt_lo, o_lo, 0, 1, 8, 9, 2, 3, 10, 11),
                             __builtin_shufflevector(dt_lo, o_lo, 4, 5, 12, 13, 6, 7, 14, 15),
                             __builtin_shufflevector(dt_hi, o_hi, 0, 1, 8, 9, 2, 3, 10, 11),
                             __builtin_shufflevector(dt_hi, o_hi, 4, 5, 12, 13, 6, 7, 14, 15)};
    const Lane8i mask[4] = {__builtin_shufflevector(nearer, nearer, 0, 0, 0, 0, 1, 1, 1, 1),
                            __builtin_shufflevector(nearer, nearer, 2, 2, 2, 2, 3, 3, 3, 3),
                            __builtin_shufflevector(nearer, nearer, 4, 4, 4, 4, 5, 5, 5, 5),
                            __builtin_shufflevector(nearer, nearer, 6, 6, 6, 6, 7, 7, 7, 7)};
    char* bytes = reinterpret_cast<char*>(f);
    for (int i = 0; i < 4; ++i) {
        char* at = bytes + i * sizeof(Lane8f);
        store_lanes(at, lane_select(mask[i], fresh[i], load_lanes(at)));
    }
}

}  // namespace

void rasterize_triangle_reference(bool persp, const RasterTriangle& r,
                                  const std::array<Vec3, 3>* clip_bary, const Lattice& lat,
                                  Fragment* frags, uint32_t* tests) {
    EdgeSetup s = set_up(r, lat);
    if (s.empty) return;
    const float inv_area = 1.0f / static_cast<float>(s.area);
    for (int py = s.py0; py <= s.py1; ++py) {
        int64_t w0 = s.e0[0], w1 = s.e0[1], w2 = s.e0[2];
        Fragment* row = frags + static_cast<size_t>(py) * lat.w;
        for (int px = s.px0; px <= s.px1; ++px) {
            if ((w0 | w1 | w2) >= 0) {
                // Screen-space barycentrics λ (without the top-left bias).
                const float l1 = static_cast<float>(w1 + s.bias[1]) * inv_area;
                const float l2 = static_cast<float>(w2 + s.bias[2]) * inv_area;
                const float l0 = 1.0f - l1 - l2;
                float depth, b[3];
                if (persp) {
                    // 1/w is linear on screen: perspective-correct interpolation.
                    const float q0 = l0 * s.iw[0], q1 = l1 * s.iw[1], q2 = l2 * s.iw[2];
                    const float inv = 1.0f / (q0 + q1 + q2);
                    b[0] = q0 * inv;
                    b[1] = q1 * inv;
                    b[2] = q2 * inv;
                    depth = b[0] * s.d[0] + b[1] * s.d[1] + b[2] * s.d[2];
                } else {
                    b[0] = l0;
                    b[1] = l1;
                    b[2] = l2;
                    depth = l0 * s.d[0] + l1 * s.d[1] + l2 * s.d[2];
                }
                Fragment& frag = row[px];
                if (tests) ++tests[static_cast<size_t>(py) * lat.w + px];
                if (depth < frag.depth) {
                    float o1, o2;
                    original_bary(s, clip_bary, b[0], b[1], b[2], o1, o2);
                    frag = {depth, r.triangle, o1, o2};
                }
            }
            w0 += s.ex[0];
            w1 += s.ex[1];
            w2 += s.ex[2];
        }
        s.e0[0] += s.ey[0];
        s.e0[1] += s.ey[1];
        s.e0[2] += s.ey[2];
    }
}

void rasterize_triangle_lanes(bool persp, const RasterTriangle& r,
                              const std::array<Vec3, 3>* clip_bary, const Lattice& lat,
                              Fragment* frags, float* depths) {
    const EdgeSetup s = set_up(r, lat);
    if (s.empty) return;
    // |E_k| ≤ |dx|·|py − ya| + |dy|·|px − xa| over the box grown by 8 steps (the lanes past its
    // right side, the step past its last row): 32 bits suffice below 2^31.
    constexpr int64_t kLimit = int64_t{1} << 30;
    const int64_t grow = 8 * lat.step;
    if ((s.extent_x + grow) * (s.extent_y + grow) >= kLimit) {
        rasterize_triangle_reference(persp, r, clip_bary, lat, frags, nullptr);
        for (int py = s.py0; py <= s.py1; ++py) {  // the depth plane follows
            const size_t row = static_cast<size_t>(py) * lat.w;
            for (int px = s.px0; px <= s.px1; ++px) depths[row + px] = frags[row + px].depth;
        }
        return;
    }
    const Lane8i index = {0, 1, 2, 3, 4, 5, 6, 7};
    Lane8i lane_ex[3];  // E_k's change from lane 0 to each lane
    int32_t ex8[3], ey[3], row_e[3];
    for (int k = 0; k < 3; ++k) {
        lane_ex[k] = index * static_cast<int32_t>(s.ex[k]);
        ex8[k] = static_cast<int32_t>(8 * s.ex[k]);
        ey[k] = static_cast<int32_t>(s.ey[k]);
        row_e[k] = static_cast<int32_t>(s.e0[k]);
    }
    const int32_t bias1 = static_cast<int32_t>(s.bias[1]), bias2 = static_cast<int32_t>(s.bias[2]);
    const Lane8f inv_area = lanes(1.0f / static_cast<float>(s.area));
    const Lane8f one = lanes(1.0f);
    // Each row's span (boxes wider than the lanes): E_k ≥ 0 bounds the step j from the box's left
    // side below (ex_k > 0) or above (ex_k < 0) by −E_k/ex_k, linear in the row: j_k = A_k +
    // B_k·(py − py0), in double and widened by one step each side; the edge test still decides each
    // point exactly.
    double A[3], B[3];
    for (int k = 0; k < 3; ++k) {
        const double inv_ex = s.ex[k] != 0 ? -1.0 / static_cast<double>(s.ex[k]) : 0;
        A[k] = static_cast<double>(s.e0[k]) * inv_ex;
        B[k] = static_cast<double>(s.ey[k]) * inv_ex;
    }
    const int last = s.px1 - s.px0;           // the box's last step
    const bool spans = last >= kPacketLanes;  // else a row is one group of lanes anyway
    for (int py = s.py0; py <= s.py1; ++py) {
        const double dy = py - s.py0;
        double lo = 0, hi = last;
        bool empty = false;
        for (int k = 0; k < 3 && spans; ++k) {
            if (s.ex[k] > 0) lo = std::max(lo, A[k] + B[k] * dy);
            if (s.ex[k] < 0) hi = std::min(hi, A[k] + B[k] * dy);
            if (s.ex[k] == 0) empty |= row_e[k] < 0;  // the edge's sign is the row's
        }
        const int first = std::max(0, static_cast<int>(std::floor(lo)) - 1);
        const int end = std::min(last, static_cast<int>(std::ceil(std::max(hi, -1.0))) + 1);
        if (empty || first > end) {
            for (int k = 0; k < 3; ++k) row_e[k] += ey[k];
            continue;
        }
        const int px_end = s.px0 + end;
        Fragment* row = frags + static_cast<size_t>(py) * lat.w;
        float* row_depths = depths + static_cast<size_t>(py) * lat.w;
        int32_t w0 = row_e[0] + static_cast<int32_t>(s.ex[0]) * first;
        int32_t w1 = row_e[1] + static_cast<int32_t>(s.ex[1]) * first;
        int32_t w2 = row_e[2] + static_cast<int32_t>(s.ex[2]) * first;
        for (int px = s.px0 + first; px <= px_end; px += 8) {
            const Lane8i W0 = w0 + lane_ex[0], W1 = w1 + lane_ex[1], W2 = w2 + lane_ex[2];
            w0 += ex8[0];
            w1 += ex8[1];
            w2 += ex8[2];
            const int n = std::min(8, px_end - px + 1);  // lanes within the span
            const Lane8i inside = lane_ge(W0 | W1 | W2, Lane8i{}) & lane_lt(index, lanes_i(n));
            const unsigned in = lane_bits(inside);
            if (!in) continue;
            // Screen-space barycentrics λ (without the top-left bias), as the reference.
            const Lane8f l1 = __builtin_convertvector(W1 + bias1, Lane8f) * inv_area;
            const Lane8f l2 = __builtin_convertvector(W2 + bias2, Lane8f) * inv_area;
            const Lane8f l0 = one - l1 - l2;
            Lane8f depth, b0, b1, b2;
            if (persp) {
                const Lane8f q0 = l0 * s.iw[0], q1 = l1 * s.iw[1], q2 = l2 * s.iw[2];
                const Lane8f inv = one / (q0 + q1 + q2);
                b0 = q0 * inv;
                b1 = q1 * inv;
                b2 = q2 * inv;
            } else {
                b0 = l0;
                b1 = l1;
                b2 = l2;
            }
            depth = b0 * s.d[0] + b1 * s.d[1] + b2 * s.d[2];
            Fragment* f = row + px;
            const Lane8f held = load_lanes(row_depths + px);  // lanes ≥ n: padding or next row
            const Lane8i nearer = lane_lt(depth, held) & inside;
            unsigned pass = lane_bits(nearer);
            if (!pass) continue;
            store_lanes(row_depths + px, lane_select(nearer, depth, held));
            if (n == kPacketLanes && !clip_bary) {  // eight fragments in the row: blended
                store_fragments(f, nearer, depth, r.triangle, s.swapped ? b2 : b1,
                                s.swapped ? b1 : b2);
                continue;
            }
            while (pass) {
                const int k = __builtin_ctz(pass);
                pass &= pass - 1;
                float o1, o2;
                original_bary(s, clip_bary, b0[k], b1[k], b2[k], o1, o2);
                f[k] = {depth[k], r.triangle, o1, o2};
            }
        }
        row_e[0] += ey[0];
        row_e[1] += ey[1];
        row_e[2] += ey[2];
    }
}

}  // namespace luz
