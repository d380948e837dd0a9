// Image: a float RGB image in linear values, the output of every pipeline; PixelRect, a
// rectangle of its pixels; AaMask, the pixels adaptive antialiasing refined.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <new>
#include <vector>

#include "luz/vec3.h"

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

/// The pixels [x0, x1) × [y0, y1).
struct PixelRect {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    int width() const { return x1 - x0; }
    int height() const { return y1 - y0; }
    bool empty() const { return x1 <= x0 || y1 <= y0; }
    bool overlaps(const PixelRect& o) const {
        return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1;
    }
    PixelRect clipped(const PixelRect& o) const {
        return {std::max(x0, o.x0), std::max(y0, o.y0), std::min(x1, o.x1), std::min(y1, o.y1)};
    }
};

/// Which pixels adaptive antialiasing refined and how deeply (`--aa-mask`).
struct AaMask {
    int width = 0, height = 0;
    std::vector<uint8_t> level;  ///< per pixel, row-major: times split (0: not refined)
};

}  // namespace luz
