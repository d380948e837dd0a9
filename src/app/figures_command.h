// `luz figures [-o DIR]`: regenerates the lecture's figures from luz's own scenes into DIR with
// DIR/index.html, by running the figures program (src/figures/luz_figures.py) on this binary.
#pragma once

#include <string>

namespace CLI {
class App;
}

namespace luz {

struct FiguresOptions {
    std::string out = "figures";  ///< the folder to (re)create
};

/// Declares the figures options on `cmd`.
void add_figures_options(CLI::App& cmd, FiguresOptions& o);

/// Runs `luz figures`: writes everything into a temporary folder next to DIR and renames it
/// into place only when every figure succeeded (an existing DIR is replaced only then).
/// Returns 0 on success, 2 when DIR names an existing non-folder or its parent is missing,
/// 1 on any other failure (unwritable place, python3 or matplotlib missing, a failed render).
int run_figures(const FiguresOptions& o);

}  // namespace luz
