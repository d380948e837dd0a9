// The tiles the samplers work in: their size, their order, the region a render computes, what
// a work item counted, and progress by pixels finished.
#pragma once

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <vector>

#include "render/render.h"
#include "render/work_items.h"

namespace luz {

/// What a sampler counted in one work item; items are summed in order.
struct SamplerCounts {
    uint64_t samples = 0;         ///< colour evaluations
    uint64_t pixels_refined = 0;  ///< adaptive: pixels split at least once

    void add(const SamplerCounts& o) {
        samples += o.samples;
        pixels_refined += o.pixels_refined;
    }
};

/// Side of the square tiles the samplers work in (pixels).
inline constexpr int kSamplerTile = 16;
/// Samples of a tile taken together (sample_points()) when a tile has no antialiasing, in row
/// order (four rows of a whole tile): the batch whose ray trees the ray tracer traces side by
/// side (BatchTracer::samples()). Progress moves by these runs.
inline constexpr int kSamplerRun = 64;
/// The work (work_of(): rays, for the ray tracer) a pixel's samples take on average above which
/// the pixels after them are taken one at a time, so that progress moves pixel by pixel even
/// when one pixel takes seconds (an exploding ray tree); a tile's first pixel is taken alone to
/// find out.
inline constexpr uint64_t kHeavyPixelWork = 4096;

/// The work a work item's counters have counted so far (rays, for the ray tracer's counters:
/// render/whitted.h overloads it); progress is reported sooner after costly pixels.
template <class Counters>
uint64_t work_of(const Counters&) {
    return 0;
}

/// The primary rays a work item's counters have counted (render/whitted.h overloads it): how a
/// render shared among processes reports each one's share (docs/DISTRIBUTED.md).
template <class Counters>
uint64_t primary_rays_of(const Counters&) {
    return 0;
}

/// Progress by pixels finished (not only by tiles), reported to RenderControl::progress: each
/// work item calls pixel() after every pixel; a count is handed over at the end of every
/// kFlushPixels pixels (a tile's worth), or at once after a pixel whose work (rays) was large,
/// so that the bar moves even when single pixels take seconds. The shared count is touched
/// rarely: an atomic add every 16 pixels, its cache line passed between the cores, was 4 % of a
/// 3200×2400 Whitted render on two cores. With tiles rendered in a scattered order
/// (tile_order()), the share of pixels done is an unbiased estimate of the share of work.
class PixelProgress {
  public:
    PixelProgress(const RenderControl& control, uint64_t total_pixels)
        : control_(control), total_(total_pixels ? total_pixels : 1) {}

    /// One work item's reports: a local count, handed over now and then.
    template <class Counters>
    struct Item {
        PixelProgress& p;
        const Counters& counters;
        uint64_t pending = 0, work_at_flush = 0;

        void pixel() {
            ++pending;
            const uint64_t work = work_of(counters);
            if (pending >= kFlushPixels || work - work_at_flush >= kFlushWork) {
                p.add(pending);
                pending = 0;
                work_at_flush = work;
            }
        }
        ~Item() {
            if (pending) p.add(pending);
        }
    };

    void add(uint64_t pixels) {
        const uint64_t done = done_.fetch_add(pixels, std::memory_order_relaxed) + pixels;
        if (control_.progress) control_.progress(static_cast<double>(done) / total_);
    }

  private:
    static constexpr uint64_t kFlushPixels = kSamplerTile * kSamplerTile;  ///< pixels, at most
    static constexpr uint64_t kFlushWork = 2048;  ///< rays after which a count is handed over
    const RenderControl& control_;
    uint64_t total_;
    alignas(64) std::atomic<uint64_t> done_{0};  ///< on a cache line of its own
};

/// The pixels a render computes: RenderControl::region (inside the image), or the whole image.
inline PixelRect render_window(const RenderControl& control, int width, int height) {
    const PixelRect whole{0, 0, width, height};
    return control.region.empty() ? whole : control.region.clipped(whole);
}

/// The pixels whose top-left corners adaptive's pass 1 computes for the pixels of `window`:
/// `window` grown by one pixel to the right and below (inside the image), for the corners of
/// its last column and row.
inline PixelRect corner_window(const PixelRect& window, int width, int height) {
    return {window.x0, window.y0, std::min(width, window.x1 + 1), std::min(height, window.y1 + 1)};
}

/// The order in which tiles are rendered: a fixed pseudo-random permutation of 0 … count−1
/// (the same in every run), so that costly regions are spread over the whole render and the
/// progress bar's time left stays honest. The image does not depend on the order.
std::vector<size_t> tile_order(size_t count);

}  // namespace luz
