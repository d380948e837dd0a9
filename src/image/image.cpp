// Image pixel storage (image.h): large blocks on huge pages where the system offers them
// (math/huge_pages.h).
#include "image/image.h"

#include <algorithm>

#include "math/huge_pages.h"

namespace luz {

void* allocate_pixels(size_t bytes) { return allocate_huge(bytes); }

Image crop(const Image& img, int x0, int y0, int w, int h) {
    Image out(w, h, Unwritten{});
    for (int y = 0; y < h; ++y) std::copy_n(&img.at(x0, y0 + y), w, &out.at(0, y));
    return out;
}

}  // namespace luz
