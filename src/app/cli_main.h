// The `luz` command line as a function: `luz` runs it, and so does rank 0 of `luz-mpi`.
#pragma once

#include <string>

#include "app/render_command.h"

namespace luz {

/// Parses and runs a `luz` command line; returns the exit status (0, 2 bad input with one line
/// on standard error, 1 other failures, 128 + signal when interrupted). `render_frame`, when
/// set, renders each frame of `luz render` (luz-mpi); otherwise luz::render() does.
int luz_main(int argc, char** argv, const FrameRenderer* render_frame);

/// Prints `message` on standard error as exactly one line (luz::one_line()).
void print_error_line(const std::string& message);

}  // namespace luz
