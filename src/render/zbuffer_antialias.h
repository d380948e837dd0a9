// Antialiasing in the zbuffer (docs/SCENES.md#antialiasing): the raster layout each mode needs, the
// grid lattice per tile, and the adaptive corner and refinement passes per tile
// (docs/ARCHITECTURE.md).
#pragma once

#include "image/image.h"
#include "render/rasterizer.h"
#include "render/sampler.h"
#include "render/stats.h"
#include "render/zbuffer_shade.h"

namespace luz {

/// The raster layout antialiasing `aa` needs on a width × height image: grid makes the
/// fixed-point unit a multiple of 2s and shrinks the tiles; adaptive uses the samplers' tiles.
RasterLayout antialias_layout(const AntialiasDesc& aa, const GridSpec& grid, int width, int height);

/// Grid antialiasing of tile `t`: the samples of its pixels (and of the ring the tent filter
/// reaches) rasterized as one lattice, shaded, then filtered into `out`.
/// Out: an Image (colours) or a TermOut (colours and terms; zbuffer_antialias.cpp has both).
template <class Out>
void grid_tile(const ZbufferFrame& f, size_t t, const GridSpec& g, Out& out, RenderStats& stats);

/// Adaptive pass 1 for tile `t`: the pixel corners of corner_rect(), rasterized and shaded
/// into `corners` ((W+1) × (H+1), row-major; Rgb or TermSample).
template <class S>
void adaptive_corners_tile(const ZbufferFrame& f, size_t t, S* corners, RenderStats& stats);

/// Adaptive pass 2 for tile `t`: pixels whose corners differ are refined on their finest
/// lattice (refine_tile()); writes the pixels into `out` and their levels into `mask`.
template <class Out>
void adaptive_refine_tile(const ZbufferFrame& f, size_t t, const AdaptiveSpec& spec,
                          const SampleFor<Out>* corners, Out& out, AaMask* mask,
                          RenderStats& stats);

}  // namespace luz
