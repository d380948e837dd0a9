// Image pixel storage (image.h): large blocks on huge pages where the system offers them.
#include "image/image.h"

#include <algorithm>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace luz {

void* allocate_pixels(size_t bytes) {
    constexpr size_t kHuge = size_t{2} << 20;
    void* p = nullptr;
    if (bytes >= 2 * kHuge) {
        const size_t rounded = (bytes + kHuge - 1) / kHuge * kHuge;
        p = std::aligned_alloc(kHuge, rounded);
#if defined(__linux__) && defined(MADV_HUGEPAGE)
        if (p) madvise(p, rounded, MADV_HUGEPAGE);  // advice only: failure changes nothing
#endif
    } else {
        p = std::malloc(bytes > 0 ? bytes : 1);
    }
    if (!p) throw std::bad_alloc();
    return p;
}

Image crop(const Image& img, int x0, int y0, int w, int h) {
    Image out(w, h, Unwritten{});
    for (int y = 0; y < h; ++y) std::copy_n(&img.at(x0, y0 + y), w, &out.at(0, y));
    return out;
}

}  // namespace luz
