// The embedded files: scenes/bunny.obj is included byte for byte by the assembler (.incbin) at
// build time; CMake passes the folder (LUZ_SCENES_DIR) and rebuilds this file when it changes.
#include "scene/embedded_files.h"

#ifndef LUZ_SCENES_DIR
#error "LUZ_SCENES_DIR must name the scenes/ folder (set by CMakeLists.txt)"
#endif

// begin/end symbols around each file's bytes, in read-only data.
asm(".pushsection .rodata\n"
    ".global luz_embedded_bunny_obj_begin\n"
    "luz_embedded_bunny_obj_begin:\n"
    ".incbin \"" LUZ_SCENES_DIR
    "/bunny.obj\"\n"
    ".global luz_embedded_bunny_obj_end\n"
    "luz_embedded_bunny_obj_end:\n"
    ".byte 0\n"
    ".popsection\n");

extern "C" const char luz_embedded_bunny_obj_begin[];
extern "C" const char luz_embedded_bunny_obj_end[];

namespace luz {

std::optional<std::string_view> embedded_file(std::string_view name) {
    if (name == "bunny.obj") {
        return std::string_view(luz_embedded_bunny_obj_begin,
                                luz_embedded_bunny_obj_end - luz_embedded_bunny_obj_begin);
    }
    return std::nullopt;
}

}  // namespace luz
