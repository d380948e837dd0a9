// `luz web [-o DIR]`: the page built by web/ (Emscripten), whose bytes app/web_page_bytes.cpp
// holds when the build made it (LUZ_HAVE_WEB_PAGE), written out as DIR/luz.html.
#include "app/web_command.h"

#include <CLI/CLI.hpp>
#include <filesystem>

#include "app/cli_main.h"
#include "luz/luz.h"

#ifdef LUZ_HAVE_WEB_PAGE  // app/web_page_bytes.cpp
extern "C" const char luz_web_html_begin[];
extern "C" const char luz_web_html_end[];
#endif

namespace luz {

namespace fs = std::filesystem;

void add_web_options(CLI::App& cmd, WebOptions& o) {
    cmd.add_option("-o,--out", o.out, "folder to write luz.html into (default: .)");
}

std::string_view embedded_web_page() {
#ifdef LUZ_HAVE_WEB_PAGE
    return std::string_view(luz_web_html_begin, luz_web_html_end - luz_web_html_begin);
#else
    return {};
#endif
}

int run_web(const WebOptions& o) {
    const std::string_view page = embedded_web_page();
    if (page.empty()) {
        print_error_line(
            "luz web: this luz was built without the web page (Emscripten's emcc was not found "
            "when it was configured): apt-get install emscripten node-acorn, then configure "
            "again (cmake -DLUZ_WEB=ON) and build");
        return 2;
    }
    std::error_code ec;
    const fs::path dir = o.out.empty() ? fs::path(".") : fs::path(o.out);
    const fs::file_status st = fs::status(dir, ec);
    if (fs::exists(st) && !fs::is_directory(st)) {
        print_error_line("luz web: -o " + o.out + ": exists and is not a folder");
        return 2;
    }
    if (!fs::exists(st)) {
        const fs::path parent = dir.has_parent_path() ? dir.parent_path() : fs::path(".");
        if (!fs::is_directory(parent, ec)) {
            print_error_line("luz web: -o " + o.out + ": its folder " + parent.string() +
                             " does not exist");
            return 2;
        }
        if (!fs::create_directory(dir, ec) && ec) {
            print_error_line("luz web: -o " + o.out + ": " + ec.message());
            return 1;
        }
    }
    write_files_together({{(dir / "luz.html").string(), std::string(page)}});
    return 0;
}

}  // namespace luz
