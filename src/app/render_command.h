// `luz render`: load, check, render and write one scene (docs/CLI.md).
#pragma once

#include <functional>

#include "app/cli_options.h"
#include "luz/render.h"
#include "luz/render_png.h"
#include "luz/scene.h"
#include "luz_engine.h"

namespace luz {

/// Runs `luz render` with `o`; returns 0 on success. Bad input throws InputError (exit 2),
/// anything else std::exception (exit 1); on failure no output file is left behind.
int run_render(const RenderArgs& o);

/// How a front end renders one frame, whole or as a PNG file: luz::render() and render_png() in
/// one process, a share of the tiles per process under MPI (src/mpi/).
struct FrameRenderer {
    std::function<Frame(const Scene&, const SceneDesc&, const RenderOptions&, const EngineHooks&)>
        whole;
    std::function<PngFrame(const Scene&, const SceneDesc&, const RenderOptions&, Encoding,
                           const EngineHooks&)>
        png;
};

/// run_render() with each frame rendered by `render_frame`.
int run_render(const RenderArgs& o, const FrameRenderer& render_frame);

}  // namespace luz
