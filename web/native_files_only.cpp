// What the web build leaves out, needing libpng and zlib (not in the browser): the PNG band
// writer (RenderOptions::png) and the checkpoint file (RenderControl's checkpoint). The page
// asks for neither (src/web/web_bindings.cpp): reaching one is a programming error.
#include <stdexcept>

#include "image/image_io.h"
#include "render/checkpoint_file.h"

namespace luz {

namespace {
[[noreturn]] void not_in_the_web_build(const char* what) {
    throw std::logic_error(std::string(what) + " is not part of the web build");
}
}  // namespace

struct PngBands::Bands {};
PngBands::PngBands(int width, int height, Encoding e)
    : width_(width), height_(height), encoding_(e) {
    not_in_the_web_build("PNG writing (RenderOptions::png)");
}
PngBands::~PngBands() = default;
void PngBands::add(const Image&, int) { not_in_the_web_build("PNG writing"); }
std::string PngBands::finish() { not_in_the_web_build("PNG writing"); }

uint32_t tile_checksum(uint64_t, std::string_view) { not_in_the_web_build("--checkpoint"); }
std::vector<std::string_view> checkpoint_pieces(uint64_t, uint64_t,
                                                const std::vector<CheckpointTileRef>&,
                                                std::string&) {
    not_in_the_web_build("--checkpoint");
}

}  // namespace luz
