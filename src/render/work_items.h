// One pass over a render's work items (tiles), run on this process's threads: each restored
// from a --checkpoint that holds it and kept there once done (render/checkpoint.h), or, under
// MPI, shared with the other processes (render/tile_share.h): the items handed out to this
// process are rendered here and the bytes of the others arrive. A tile's pixels do not depend
// on where or in which order it was rendered, so the image is the same bits either way.
#pragma once

#include <algorithm>
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
// Spelled out for compilers without C++20's deduction for aggregates (Clang before 17:
// the web build's Emscripten).
template <class Render, class Write, class Read>
TileCode(Render, Write, Read) -> TileCode<Render, Write, Read>;

/// code.read(t, in); false when `in` is short (read_raw() throws).
template <class Code>
bool read_tile(Code& code, size_t t, std::string_view& in) {
    try {
        code.read(t, in);
        return true;
    } catch (const InputError&) {
        return false;
    }
}

/// Puts back tile t (item base + t) from the checkpoint: exactly its bytes, or InputError.
template <class Code>
void read_saved(Code& code, const Checkpoint& checkpoint, size_t base, size_t t) {
    std::string_view in = checkpoint.data(base + t);
    const bool whole = read_tile(code, t, in);
    if (!whole || !in.empty()) {
        throw InputError(checkpoint.path() + ": --checkpoint: damaged checkpoint (tile " +
                         std::to_string(base + t) + " is " + (whole ? "long" : "short") + ")");
    }
}

/// Passes a checkpoint's warning (a failed periodic write) on, if any.
inline void warn(const RenderControl& control, const std::string& message) {
    if (!message.empty() && control.warning) control.warning(message);
}

template <class Code, class Elsewhere, class Rays>
void run_shared(const RenderControl& control, Checkpoint* checkpoint,
                const std::vector<size_t>& list, size_t base, bool everyone, Code& code,
                Elsewhere&& elsewhere, Rays&& rays);

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
    if (!control.share) {
        parallel_items(control.threads, list.size(), [&](size_t item) {
            if (cancelled()) return;
            const size_t t = list[item];
            if (checkpoint && checkpoint->done(base + t)) {
                read_saved(code, *checkpoint, base, t);
                elsewhere(t);
                return;
            }
            code.render(t);
            if (checkpoint && !cancelled()) {
                std::string bytes;
                code.write(t, bytes);
                warn(control, checkpoint->finish(base + t, std::move(bytes)));
            }
        });
        return;
    }
    // Shared: tiles are handed out in image order (not `list`'s scattered one), so that each
    // process writes a few bands of its image, not every page of it. The gathering process reads
    // back what the checkpoint holds, and no process renders it; the tiles that arrive from the
    // others are kept in the checkpoint as they come.
    std::vector<size_t> sorted = list;
    std::sort(sorted.begin(), sorted.end());
    run_shared(control, checkpoint, sorted, base, everyone, code, elsewhere, rays);
}

/// run_pass() with control.share set: `list` in the order tiles are handed out.
template <class Code, class Elsewhere, class Rays>
void run_shared(const RenderControl& control, Checkpoint* checkpoint,
                const std::vector<size_t>& list, size_t base, bool everyone, Code& code,
                Elsewhere&& elsewhere, Rays&& rays) {
    const auto cancelled = [&] {
        return control.cancel && control.cancel->load(std::memory_order_relaxed);
    };
    TileShare& share = *control.share;
    std::vector<char> held(list.size(), 0);
    if (checkpoint) {
        for (size_t item = 0; item < list.size(); ++item) {
            const size_t t = list[item];
            if (!checkpoint->done(base + t)) continue;
            read_saved(code, *checkpoint, base, t);
            elsewhere(t);
            held[item] = 1;
            share.restored(item, std::string(checkpoint->data(base + t)), rays(t));
        }
    }
    share.begin_pass(
        list.size(), everyone, held,
        [&](size_t item, std::string_view bytes) {
            elsewhere(list[item]);
            if (checkpoint)
                warn(control, checkpoint->finish(base + list[item], std::string(bytes)));
        },
        control.cancel);
    const int threads = resolve_threads(control.threads);
    parallel_items(threads, static_cast<size_t>(threads), [&](size_t) {
        for (size_t item; !cancelled() && (item = share.next()) != TileShare::kNone;) {
            const size_t t = list[item];
            code.render(t);
            std::string bytes;
            code.write(t, bytes);
            if (checkpoint && !cancelled()) warn(control, checkpoint->finish(base + t, bytes));
            share.finished(item, std::move(bytes), rays(t));
        }
    });
    for (const auto& [item, bytes] : share.end_pass()) {
        std::string_view in = bytes;
        if (!read_tile(code, list[item], in) || !in.empty())
            throw InputError("mpirun: a tile another process sent is damaged");
    }
}

}  // namespace luz
