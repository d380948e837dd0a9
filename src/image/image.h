// Image: a float RGB image in linear values, the output of every pipeline.
#pragma once

#include <cstddef>
#include <cstdlib>
#include <new>
#include <vector>

#include "math/vec3.h"

namespace luz {

/// Allocator of Image::pixels: a pixel made without a value is left unwritten (Rgb is an
/// implicit-lifetime type), so that a renderer that writes every pixel pays for the memory
/// once, in parallel, where it writes; blocks of 4 MiB and more are 2 MiB-aligned and, on
/// Linux, advised to use transparent huge pages (fewer page faults for a large image).
template <class T>
struct PixelAllocator {
    using value_type = T;
    PixelAllocator() = default;
    template <class U>
    PixelAllocator(const PixelAllocator<U>&) noexcept {}

    T* allocate(size_t n);
    void deallocate(T* p, size_t) noexcept { std::free(p); }
    template <class U>
    void construct(U*) noexcept {}  // no value: leave the memory as it is
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(static_cast<Args&&>(args)...);
    }
    template <class U>
    bool operator==(const PixelAllocator<U>&) const noexcept {
        return true;
    }
};

/// Marks the Image constructor that leaves the pixels unwritten (see PixelAllocator).
struct Unwritten {};

struct Image {
    int width = 0, height = 0;
    std::vector<Rgb, PixelAllocator<Rgb>> pixels;  ///< row-major, row 0 at the top

    Image() = default;
    Image(int w, int h, Rgb fill = Rgb{0.0f})
        : width(w), height(h), pixels(static_cast<size_t>(w) * h, fill) {}
    /// w × h pixels whose values the caller writes, every one of them, before reading any.
    Image(int w, int h, Unwritten) : width(w), height(h), pixels(static_cast<size_t>(w) * h) {}

    Rgb& at(int x, int y) { return pixels[static_cast<size_t>(y) * width + x]; }
    const Rgb& at(int x, int y) const { return pixels[static_cast<size_t>(y) * width + x]; }
};

void* allocate_pixels(size_t bytes);  // image.cpp

/// The w × h pixels of `img` whose top-left pixel is (x0, y0) (inside `img`).
Image crop(const Image& img, int x0, int y0, int w, int h);

template <class T>
T* PixelAllocator<T>::allocate(size_t n) {
    if (n > static_cast<size_t>(-1) / sizeof(T)) throw std::bad_array_new_length();
    return static_cast<T*>(allocate_pixels(n * sizeof(T)));
}

}  // namespace luz
