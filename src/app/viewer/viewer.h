// The viewer of docs/VIEWER.md (`luz view`): an SDL2 + OpenGL window with the progressively
// rendered image, a Dear ImGui panel that edits the scene live, and the ray-tree inspector.
#pragma once

#include "app/view_command.h"

namespace luz {

/// Opens the window (or, with --benchmark, measures without one) and runs until closed, or
/// until the --screenshot is written. 0 on success, 1 when the window cannot open.
int run_viewer(const ViewOptions& o);

/// `luz view --benchmark`: frames per second of each refinement pass and cancel latency,
/// printed on standard output. No window.
int run_view_benchmark(const ViewOptions& o);

}  // namespace luz
