// luz.render(): the render itself, run on a thread of its own with the GIL released while the
// calling thread waits, checks for Ctrl-C (KeyboardInterrupt) and draws the progress bar.
#pragma once

#include <pybind11/pybind11.h>

#include "luz/luz.h"
#include "python/scene_handle.h"

namespace luz::python {

/// Renders `scene` with `options` (threads, per-term images; its cancel flag and progress are
/// set here) through run_interruptibly(): Ctrl-C (KeyboardInterrupt, or any exception a signal
/// handler raises) cancels the render, joins it and raises. `progress` (None, or a callable
/// taking the fraction done) is called from the waiting thread only, never from the render's
/// threads; an exception it raises stops the render too. Call with the GIL.
Frame render_interruptibly(const SceneRef& scene, RenderOptions options, pybind11::handle progress);

}  // namespace luz::python
