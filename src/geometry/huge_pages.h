// HugePageAllocator: a std::vector allocator for the large arrays a ray visits at random (the
// BVH's nodes, the leaves' primitive blocks). From 2 MiB up it aligns them to 2 MiB and asks
// Linux for transparent huge pages (madvise MADV_HUGEPAGE, which a machine whose THP setting is
// "madvise" needs): one TLB entry then covers 2 MiB instead of 4 KiB, and a ray through a
// million-triangle scene no longer waits on page walks. Elsewhere, or when the kernel declines,
// it is plain aligned memory. Embree allocates its BVH the same way.
#pragma once

#include <cstddef>
#include <cstdlib>
#include <new>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace luz {

inline constexpr size_t kHugePage = size_t{2} << 20;

/// Memory for n bytes, 2 MiB-aligned and advised for huge pages from 2 MiB up.
inline void* allocate_huge(size_t bytes, size_t alignment) {
    if (bytes < kHugePage) {
        return ::operator new (bytes, std::align_val_t{alignment});
    }
    void* p = nullptr;
    if (posix_memalign(&p, kHugePage, bytes) != 0) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    madvise(p, bytes, MADV_HUGEPAGE);  // advice only: no huge pages is not an error
#endif
    return p;
}

inline void free_huge(void* p, size_t bytes, size_t alignment) {
    if (bytes < kHugePage) {
        ::operator delete (p, std::align_val_t{alignment});
    } else {
        std::free(p);
    }
}

template <class T>
struct HugePageAllocator {
    using value_type = T;
    HugePageAllocator() = default;
    template <class U>
    HugePageAllocator(const HugePageAllocator<U>&) {}

    T* allocate(size_t n) {
        if (n > static_cast<size_t>(-1) / sizeof(T)) throw std::bad_array_new_length();
        return static_cast<T*>(allocate_huge(n * sizeof(T), alignof(T)));
    }
    void deallocate(T* p, size_t n) { free_huge(p, n * sizeof(T), alignof(T)); }

    template <class U>
    bool operator==(const HugePageAllocator<U>&) const {
        return true;
    }
};

}  // namespace luz
