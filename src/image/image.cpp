// Image pixel storage (image.h): large blocks on huge pages where the system offers them.
#include "image/image.h"

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

}  // namespace luz
