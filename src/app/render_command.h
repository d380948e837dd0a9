// `luz render`: load, check, render and write one scene (SPEC §3).
#pragma once

#include "app/cli_options.h"

namespace luz {

/// Runs `luz render` with `o`; returns 0 on success. Bad input throws InputError (exit 2),
/// anything else std::exception (exit 1); on failure no output file is left behind.
int run_render(const RenderArgs& o);

}  // namespace luz
