// libFuzzer target: OBJ (and MTL) text → mesh (parse_obj). The input is the OBJ text, optionally
// followed by a line "#MTL" and the text every `mtllib` file reads as. Bad input must end in
// InputError; a crash, a sanitizer report or another exception is a bug.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "scene/obj_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    std::string_view obj(reinterpret_cast<const char*>(data), size);
    std::string_view mtl;
    bool has_mtl = false;
    if (const size_t at = obj.find("\n#MTL\n"); at != std::string_view::npos) {
        mtl = obj.substr(at + 6);
        obj = obj.substr(0, at + 1);
        has_mtl = true;
    }
    const luz::TextReader read = [&](const std::string&,
                                     std::string& reason) -> std::optional<std::string> {
        if (!has_mtl) {
            reason = "No such file or directory";
            return std::nullopt;
        }
        return std::string(mtl);
    };
    std::vector<std::string> warnings;
    try {
        const luz::MeshData mesh = luz::parse_obj(obj, "fuzz.obj", true, read, warnings);
        (void)mesh;
    } catch (const luz::InputError&) {
        // bad input, reported with file and line: the expected outcome
    }
    return 0;
}
