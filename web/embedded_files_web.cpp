// The embedded files in the web build: scenes/bunny.obj's bytes as an array (embedded_bunny.inc,
// made by bytes_to_c.cmake), for the same embedded_file() as scene/embedded_files.cpp.
#include "scene/embedded_files.h"

namespace {
const unsigned char kBunnyObj[] = {
#include "embedded_bunny.inc"
};
}  // namespace

namespace luz {

std::optional<std::string_view> embedded_file(std::string_view name) {
    if (name == "bunny.obj")
        return std::string_view(reinterpret_cast<const char*>(kBunnyObj), sizeof kBunnyObj);
    return std::nullopt;
}

}  // namespace luz
