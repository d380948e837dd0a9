// The window's pixels to a file.
#include "app/viewer/screenshot.h"

#include <SDL_opengl.h>

#include <cstdint>
#include <vector>

#include "luz/luz.h"

namespace luz {

void write_screenshot(const std::string& path, int width, int height) {
    std::vector<uint8_t> rgb(static_cast<size_t>(width) * height * 3);
    glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
    // OpenGL rows go bottom up; 8-bit values become v/255, written back as the same bytes.
    Image img(width, height);
    for (int y = 0; y < height; ++y) {
        const uint8_t* row = rgb.data() + static_cast<size_t>(height - 1 - y) * width * 3;
        for (int x = 0; x < width; ++x) {
            img.at(x, y) =
                Rgb{row[3 * x] / 255.0f, row[3 * x + 1] / 255.0f, row[3 * x + 2] / 255.0f};
        }
    }
    write_image(path, img, Encoding::linear);
}

}  // namespace luz
