// Progress by pixels finished (not only by tiles): each tile counts its pixels and the cost its
// colour function reported, and hands a count over now and then.
#pragma once

#include <atomic>
#include <cstdint>

#include "render/render.h"
#include "render/tiles.h"

namespace luz {

/// Progress by pixels finished, reported to RenderControl::progress: each work item calls
/// pixel() after every pixel, and cost() with what its colour function said its samples cost
/// (in progress reports' worth: render/colour_function.h); a count is handed over at the end
/// of every kFlushPixels pixels (a tile's worth), or at once after a pixel once the cost since
/// the last hand-over reached 1, so that the bar moves even when single pixels take seconds.
/// The shared count is touched rarely: its cache line is passed between the cores. With tiles
/// rendered in a scattered order (tile_order()), the share of pixels done is an unbiased
/// estimate of the share of work.
class PixelProgress {
  public:
    PixelProgress(const RenderControl& control, uint64_t total_pixels)
        : control_(control), total_(total_pixels ? total_pixels : 1) {}

    /// One work item's reports: a local count, handed over now and then.
    struct Item {
        PixelProgress& p;
        uint64_t pending = 0;
        double owed = 0;  ///< cost since the last hand-over

        void cost(double c) { owed += c; }
        void pixel() {
            ++pending;
            if (pending >= kFlushPixels || owed >= 1.0) {
                p.add(pending);
                pending = 0;
                owed = 0;
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
    const RenderControl& control_;
    uint64_t total_;
    alignas(64) std::atomic<uint64_t> done_{0};  ///< on a cache line of its own
};

}  // namespace luz
