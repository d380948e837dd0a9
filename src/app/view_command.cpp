// `luz view` options and dispatch: the viewer itself is a module (luz_viewer.so) loaded here.
#include "app/view_command.h"

#include <CLI/CLI.hpp>
#include <cstdio>

#ifdef LUZ_HAVE_VIEWER
#include <dlfcn.h>

#include <filesystem>
#include <string>
#include <system_error>
#include <vector>
#endif

namespace luz {

void add_view_options(CLI::App& cmd, ViewOptions& o) {
    cmd.add_option("SCENE", o.scene, "scene file (JSON, or NFF: .nff), or demo:NAME")->required();
    cmd.add_option("--set", o.sets, "override a scene key by dotted path; repeatable")
        ->type_name("PATH=JSON")
        ->allow_extra_args(false);
    cmd.add_option("--screenshot", o.screenshot,
                   "render the window (image and panel) to this file once the image is "
                   "finished, then exit");
    cmd.add_option("--click", o.click,
                   "X,Y: inspect pixel (X, Y)'s ray tree (with --screenshot, also written as "
                   "JSON next to it)");
    cmd.add_option("--aov", o.show,
                   "show this per-term image instead of the image (ambient, diffuse, ... tests; "
                   "V cycles through them)")
        ->type_name("NAME");
    cmd.add_option("--threads", o.threads, "render threads (default: all cores)")
        ->check(CLI::NonNegativeNumber);
    cmd.add_option("--width", o.width, "image width (overrides image.width)")
        ->check(CLI::PositiveNumber);
    cmd.add_option("--height", o.height, "image height (overrides image.height)")
        ->check(CLI::PositiveNumber);
    cmd.add_flag("--benchmark", o.benchmark,
                 "no window: print the preview's refinement passes per second");
}

#ifdef LUZ_HAVE_VIEWER
namespace {

/// Where luz_viewer.so is: beside the running binary (a build tree), else where `cmake
/// --install` puts it relative to the binary (LUZ_VIEWER_FROM_BINDIR: bin/ → lib/…/luz/).
std::vector<std::string> viewer_module_paths() {
    std::error_code ec;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (ec) return {"luz_viewer.so"};
    const std::filesystem::path dir = exe.parent_path();
    return {(dir / "luz_viewer.so").string(),
            (dir / LUZ_VIEWER_FROM_BINDIR / "luz_viewer.so").lexically_normal().string()};
}

}  // namespace
#endif

int run_view(const ViewOptions& o) {
#ifdef LUZ_HAVE_VIEWER
    // The viewer is a module loaded on demand: `luz render` and the rest never load SDL2.
    std::string tried;
    for (const std::string& path : viewer_module_paths()) {
        if (!std::filesystem::exists(path)) {
            tried += "\n  " + path + ": not found";
            continue;
        }
        void* module = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!module) {
            tried += "\n  " + path + ": " + dlerror();
            continue;
        }
        using Run = int (*)(const ViewOptions*);
        if (auto run = reinterpret_cast<Run>(dlsym(module, "luz_viewer_run"))) return run(&o);
        tried += "\n  " + path + ": no luz_viewer_run";
    }
    std::fprintf(stderr, "luz view: cannot load the viewer module luz_viewer.so:%s\n",
                 tried.c_str());
    return 1;
#else
    (void)o;
    std::fprintf(stderr,
                 "luz view: this luz was built without the viewer (needs SDL2, Dear ImGui and "
                 "OpenGL: libsdl2-dev, libimgui-dev, libgl-dev)\n");
    return 1;
#endif
}

}  // namespace luz
