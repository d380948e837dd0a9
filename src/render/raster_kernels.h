// The rasterizer's per-triangle kernels: the plain reference, one lattice point at a time, and
// the eight-lane one the zbuffer runs (eight points of a row per step, 32-bit edge functions);
// the two give the same fragments bit for bit (tests/render/raster_kernels_test.cpp).
#pragma once

#include <array>
#include <cstdint>

#include "math/vec3.h"
#include "render/rasterizer.h"

namespace luz {

/// ⌊a / b⌋ and ⌈a / b⌉ for b > 0.
inline int64_t floor_div(int64_t a, int64_t b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }
inline int64_t ceil_div(int64_t a, int64_t b) { return -floor_div(-a, b); }

/// Rasterizes triangle `r` into the fragments of lattice `lat` (top-left fill rule, nearest
/// depth kept, ties to the fragment already there), one point at a time with 64-bit edge
/// functions. `clip_bary`: the barycentrics of a clipped piece's vertices in the original
/// triangle, or null. `tests` (or null) counts each point's depth tests (docs/SCENES.md#terms
/// `tests`).
void rasterize_triangle_reference(bool perspective, const RasterTriangle& r,
                                  const std::array<Vec3, 3>* clip_bary, const Lattice& lat,
                                  Fragment* frags, uint32_t* tests);

/// The same fragments as rasterize_triangle_reference() without `tests`, eight points of a row
/// at a time with 32-bit edge functions; triangles too large for 32 bits go to the reference.
/// `depths` holds frags[i].depth at i, and is kept so: lat.w·lat.h floats and 8 more (read and
/// written back unchanged past a row's end).
void rasterize_triangle_lanes(bool perspective, const RasterTriangle& r,
                              const std::array<Vec3, 3>* clip_bary, const Lattice& lat,
                              Fragment* frags, float* depths);

}  // namespace luz
