// `luz view` options and dispatch.
#include "app/view_command.h"

#include <CLI/CLI.hpp>
#include <cstdio>

#ifdef LUZ_HAVE_VIEWER
#include "app/viewer/viewer.h"
#endif

namespace luz {

void add_view_options(CLI::App& cmd, ViewOptions& o) {
    cmd.add_option("SCENE", o.scene, "scene file, or demo:NAME")->required();
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

int run_view(const ViewOptions& o) {
#ifdef LUZ_HAVE_VIEWER
    return run_viewer(o);
#else
    (void)o;
    std::fprintf(stderr,
                 "luz view: this luz was built without the viewer (needs SDL2, Dear ImGui and "
                 "OpenGL: libsdl2-dev, libimgui-dev, libgl-dev)\n");
    return 1;
#endif
}

}  // namespace luz
