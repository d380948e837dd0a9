// libFuzzer target: JSON text → validated scene (parse_scene). Bad input must end in InputError
// (exit 2 in `luz`); anything else — a crash, a sanitizer report, another exception — is a bug.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <string>
#include <string_view>

#include "scene/scene_loader.h"

namespace {

/// A folder holding one small mesh (tri.obj + tri.mtl), so that seeds may name a mesh file.
std::string g_base_dir;

void make_base_dir() {
    char tmpl[] = "/tmp/luz-fuzz-scene-XXXXXX";
    if (!mkdtemp(tmpl)) std::abort();
    g_base_dir = tmpl;
    std::ofstream(g_base_dir + "/tri.obj") << "mtllib tri.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                              "vn 0 0 1\nusemtl red\nf 1//1 2//1 3//1\n";
    std::ofstream(g_base_dir + "/tri.mtl") << "newmtl red\nKd 0.8 0.1 0.1\nNs 30\nillum 3\n";
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    make_base_dir();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    try {
        luz::SceneDesc desc = luz::parse_scene(text, "fuzz.json", g_base_dir);
        (void)desc;
    } catch (const luz::InputError&) {
        // bad input, reported with file and place: the expected outcome
    }
    return 0;
}
