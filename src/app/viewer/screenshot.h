// Screenshot: the window's current OpenGL back buffer to an image file (`--screenshot`).
#pragma once

#include <string>

namespace luz {

/// Reads the back buffer (width × height pixels, after drawing and before the swap) and writes
/// it to `path` (format by extension, atomically; image_io.h).
void write_screenshot(const std::string& path, int width, int height);

}  // namespace luz
