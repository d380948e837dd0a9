// The viewer module's entry point: `luz view` loads luz_viewer.so (dlopen) and calls it, so that
// the rest of luz starts without SDL2, OpenGL and the libraries they bring (view_command.cpp).
#include "app/viewer/viewer.h"

extern "C" __attribute__((visibility("default"))) int luz_viewer_run(const luz::ViewOptions* o) {
    return luz::run_viewer(*o);
}
