// The tile store of the samplers: a layer around "render tile t" that keeps each tile's counters
// and counts, gives it its progress, and restores, keeps (--checkpoint) or hands out (MPI) its
// bytes through run_pass() (render/work_items.h).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "render/checkpoint.h"
#include "render/pixel_progress.h"
#include "render/render.h"
#include "render/tile_bytes.h"
#include "render/tiles.h"
#include "render/work_items.h"

namespace luz {

/// What rendering one tile works with: its counters (of the colour function), its counts and
/// its progress.
template <class Counters>
struct TileWork {
    Counters& counters;
    SamplerCounts& counts;
    PixelProgress::Item& progress;
};

/// The work items of a render's passes over `tiles` (item pass·count + t: tile t of that pass),
/// each counted into a local copy first, so that threads never write to one cache line; their
/// counters end in `counters`, in item order, to be summed by the caller. Progress counts the
/// window's pixels once per pass.
template <class Counters>
class TileStore {
  public:
    TileStore(const RenderControl& control, const TileGrid& tiles, size_t passes,
              std::vector<Counters>& counters)
        : control_(control),
          tiles_(tiles),
          counters_(counters),
          counts_(passes * tiles.count),
          progress_(control,
                    static_cast<uint64_t>(tiles.window.width()) * tiles.window.height() * passes) {
        counters_.assign(passes * tiles.count, Counters{});
        if (control.checkpoint) control.checkpoint->start(passes * tiles.count);
    }

    /// Pass `pass` over the tiles `list`: render(t, work) renders tile t here (work: a
    /// TileWork); bytes(t, io) describes what it made for a TileWriter or a TileReader, after
    /// the tile's counters and counts. `everyone`: every process needs every tile's bytes
    /// (TileShare::begin_pass).
    template <class Render, class Bytes>
    void pass(size_t pass, const std::vector<size_t>& list, bool everyone, Render&& render,
              Bytes&& bytes) {
        const size_t base = pass * tiles_.count;
        const auto both_ways = [&](size_t t, auto& io) {
            io.raw(counters_[base + t]);
            io.raw(counts_[base + t]);
            bytes(t, io);
        };
        auto code = TileCode{[&](size_t t) {
                                 Counters c{};
                                 SamplerCounts n;
                                 {
                                     PixelProgress::Item tick{progress_};
                                     TileWork<Counters> work{c, n, tick};
                                     render(t, work);
                                 }
                                 counters_[base + t] = c;
                                 counts_[base + t] = n;
                             },
                             [&](size_t t, std::string& o) {
                                 TileWriter w{o};
                                 both_ways(t, w);
                             },
                             [&](size_t t, std::string_view& in) {
                                 TileReader r{in};
                                 both_ways(t, r);
                             }};
        // A tile rendered elsewhere counts its pixels when its bytes arrive; its samples are
        // the primary rays of a ray-traced tile (the share's statistics).
        run_pass(
            control_, control_.checkpoint, list, base, everyone, code,
            [&](size_t t) { progress_.add(tiles_.pixels(t)); },
            [&](size_t t) { return counts_[base + t].samples; });
    }

    /// The counts of every item, summed in item order.
    SamplerCounts total() const {
        SamplerCounts sum;
        for (const SamplerCounts& c : counts_) sum.add(c);
        return sum;
    }

  private:
    const RenderControl& control_;
    const TileGrid& tiles_;
    std::vector<Counters>& counters_;
    std::vector<SamplerCounts> counts_;
    PixelProgress progress_;
};

}  // namespace luz
