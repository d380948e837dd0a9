// Memory on transparent huge pages for the large arrays the renderer visits at random or writes
// once: the scene BVH's nodes and primitive blocks (HugePageAllocator), an image's pixels
// (image/image.h). From 4 MiB up an array is 2 MiB-aligned, rounded up to whole 2 MiB pages and
// advised to use huge pages (madvise MADV_HUGEPAGE, which a machine whose THP setting is
// "madvise" needs): one TLB entry then covers 2 MiB instead of 4 KiB, so that a ray through a
// million-triangle scene waits less on page walks and a large image takes fewer page faults.
// Embree allocates its BVH the same way. Elsewhere, or when the kernel declines, it is plain
// aligned memory. Always freed with std::free.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <new>
#include <type_traits>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace luz {

inline constexpr size_t kHugePage = size_t{2} << 20;

/// `bytes` of memory aligned to `alignment` (a power of two), on huge pages from 4 MiB up;
/// throws std::bad_alloc when there is none. Free it with std::free.
inline void* allocate_huge(size_t bytes, size_t alignment = alignof(std::max_align_t)) {
    if (bytes > static_cast<size_t>(PTRDIFF_MAX) / 2) throw std::bad_alloc();  // no such memory
    const bool huge = bytes >= 2 * kHugePage;
    const size_t align = huge ? kHugePage : (alignment > sizeof(void*) ? alignment : sizeof(void*));
    const size_t rounded = ((bytes > 0 ? bytes : 1) + align - 1) / align * align;
    void* p = std::aligned_alloc(align, rounded);
    if (!p) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    if (huge) madvise(p, rounded, MADV_HUGEPAGE);  // advice only: no huge pages is not an error
#endif
    return p;
}

/// A std::vector allocator on allocate_huge().
template <class T>
struct HugePageAllocator {
    using value_type = T;
    HugePageAllocator() = default;
    template <class U>
    HugePageAllocator(const HugePageAllocator<U>&) noexcept {}

    T* allocate(size_t n) {
        if (n > static_cast<size_t>(-1) / sizeof(T)) throw std::bad_array_new_length();
        return static_cast<T*>(allocate_huge(n * sizeof(T), alignof(T)));
    }
    void deallocate(T* p, size_t) noexcept { std::free(p); }

    template <class U>
    bool operator==(const HugePageAllocator<U>&) const noexcept {
        return true;
    }
};

/// A std::vector on huge pages when large.
template <class T>
using HugeVector = std::vector<T, HugePageAllocator<T>>;

struct FreeHuge {
    void operator()(void* p) const noexcept { std::free(p); }
};
/// An array of trivial T left uninitialized (scratch filled before it is read), on huge pages
/// when large: make_huge_array<T>(n).
template <class T>
using HugeArray = std::unique_ptr<T[], FreeHuge>;

template <class T>
HugeArray<T> make_huge_array(size_t n) {
    static_assert(std::is_trivially_default_constructible_v<T> &&
                  std::is_trivially_destructible_v<T>);
    if (n > static_cast<size_t>(-1) / sizeof(T)) throw std::bad_array_new_length();
    return HugeArray<T>(static_cast<T*>(allocate_huge(n * sizeof(T), alignof(T))));
}

}  // namespace luz
