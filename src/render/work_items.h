// One pass over a render's work items (tiles), run on this process's threads: each restored
// from a --checkpoint that holds it and kept there once done (render/checkpoint.h), or, under
// MPI, shared with the other processes (render/tile_share.h): the items handed out to this
// process are rendered here and the bytes of the others arrive. A tile's pixels do not depend
// on where or in which order it was rendered, so the image is the same bits either way.
#pragma once

#include <atomic>
#include <string>
#include <string_view>
#include <vector>

#include "render/checkpoint.h"
#include "render/parallel.h"
#include "render/render.h"
#include "render/tile_share.h"
#include "scene/input_error.h"

namespace luz {

/// What a pass does with tile t: render(t) renders it; write(t, bytes) appends what it made
/// (its counters, its pixels); read(t, in) puts that back, consuming `in`.
template <class Render, class Write, class Read>
struct TileCode {
    Render render;
    Write write;
    Read read;
};

/// Runs `code` over the tiles `list`. `base` + t is tile t's item number in the checkpoint;
/// `everyone`: every process needs every tile (see TileShare::begin_pass). `elsewhere(t)` is
/// called for a tile not rendered here, when its bytes are read back or arrive (progress);
/// `rays(t)` gives the primary rays tile t traced (stats of a shared render).
template <class Code, class Elsewhere, class Rays>
void run_pass(const RenderControl& control, Checkpoint* checkpoint, const std::vector<size_t>& list,
              size_t base, bool everyone, Code& code, Elsewhere&& elsewhere, Rays&& rays) {
    const auto cancelled = [&] {
        return control.cancel && control.cancel->load(std::memory_order_relaxed);
    };
    const auto read_all = [&](size_t t, std::string_view in, const char* damaged) {
        code.read(t, in);
        if (!in.empty()) throw InputError(damaged);
    };
    if (!control.share) {
        parallel_items(control.threads, list.size(), [&](size_t item) {
            if (cancelled()) return;
            const size_t t = list[item];
            if (checkpoint && checkpoint->done(base + t)) {
                read_all(t, checkpoint->data(base + t),
                         "--checkpoint: damaged checkpoint (a tile is long)");
                elsewhere(t);
                return;
            }
            code.render(t);
            if (checkpoint && !cancelled()) {
                std::string bytes;
                code.write(t, bytes);
                checkpoint->finish(base + t, std::move(bytes));
            }
        });
        return;
    }
    TileShare& share = *control.share;
    share.begin_pass(
        list.size(), everyone, [&](size_t item) { elsewhere(list[item]); }, control.cancel);
    const int threads = resolve_threads(control.threads);
    parallel_items(threads, static_cast<size_t>(threads), [&](size_t) {
        for (size_t item; !cancelled() && (item = share.next()) != TileShare::kNone;) {
            const size_t t = list[item];
            code.render(t);
            std::string bytes;
            code.write(t, bytes);
            share.finished(item, std::move(bytes), rays(t));
        }
    });
    for (const auto& [item, bytes] : share.end_pass()) {
        read_all(list[item], bytes, "mpirun: a tile another process sent is damaged (long)");
    }
}

}  // namespace luz
