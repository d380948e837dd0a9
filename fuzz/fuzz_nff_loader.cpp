// libFuzzer target: NFF text → validated scene (parse_scene on a file named *.nff,
// docs/SCENES.md#nff). Bad input must end in InputError (exit 2 in `luz`); anything else — a crash,
// a sanitizer report, another exception — is a bug.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "scene/scene_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    try {
        luz::SceneDesc desc = luz::parse_scene(text, "fuzz.nff", "");
        (void)desc;
    } catch (const luz::InputError&) {
        // bad input, reported with file and place: the expected outcome
    }
    return 0;
}
