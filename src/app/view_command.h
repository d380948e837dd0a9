// `luz view`: its options, and the dispatch to the viewer (or a message when luz was built
// without it).
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace luz {

struct ViewOptions {
    std::string scene;              ///< a file path or demo:NAME
    std::vector<std::string> sets;  ///< "PATH=JSON" overrides, in order
    std::string screenshot;         ///< headless: render the window to this file and exit
    std::string click;              ///< "X,Y": inspect this pixel's ray tree
    int threads = 0;                ///< render threads, 0: all cores
    bool benchmark = false;         ///< no window: measure the preview's passes per second
    int width = 0, height = 0;      ///< image size override (--width/--height)
    std::string show;               ///< --aov NAME: show that term instead of the image
};

/// Declares the view options on `cmd`.
void add_view_options(CLI::App& cmd, ViewOptions& o);

/// Runs `luz view`; 0 on success, 1 when luz was built without the viewer or the window
/// cannot open. Bad input throws InputError (exit 2).
int run_view(const ViewOptions& o);

}  // namespace luz
