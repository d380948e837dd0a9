// `luz web [-o DIR]`: writes DIR/luz.html, the self-contained page of docs/WEB.md (luz compiled to
// WebAssembly, web/), embedded in this binary when the build had Emscripten.
#pragma once

#include <string>
#include <string_view>

namespace CLI {
class App;
}

namespace luz {

struct WebOptions {
    std::string out = ".";  ///< the folder luz.html goes into (made when missing)
};

/// Declares the web options on `cmd`.
void add_web_options(CLI::App& cmd, WebOptions& o);

/// The embedded luz.html; empty when this luz was built without Emscripten.
std::string_view embedded_web_page();

/// Runs `luz web`: writes DIR/luz.html atomically. Returns 0; 2 (one message line) when the
/// page is not built in, DIR is not a folder or its parent is missing; 1 when it cannot be
/// written.
int run_web(const WebOptions& o);

}  // namespace luz
