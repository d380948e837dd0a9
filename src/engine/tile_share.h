// TileShare: how a render's work items (tiles) are shared with other processes
// (docs/DISTRIBUTED.md, `mpirun -np N luz render`). The renderer asks it for the items to render
// here and gives it their bytes; at the end of a pass it hands back the bytes of the items rendered
// elsewhere. Implemented over MPI in src/mpi/; a render without one renders every item itself.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace luz {

class TileShare {
  public:
    static constexpr size_t kNone = static_cast<size_t>(-1);

    virtual ~TileShare() = default;

    /// A pass of `count` items begins (every process of the render calls it, in the same
    /// order). `everyone` when every process needs every item's bytes at the end (adaptive's
    /// corners); otherwise only the process that gathers (rank 0). On the gathering process,
    /// `restored[i]` marks the items it already holds (read back from a --checkpoint; it has
    /// given their bytes with restored()): no process renders them; elsewhere it is ignored.
    /// `arrived(i, bytes)` is called on the gathering process, from any thread, as item i
    /// rendered elsewhere comes in (progress, the checkpoint). The pass ends early, without
    /// waiting for the others, once `cancel` is set.
    virtual void begin_pass(size_t count, bool everyone, const std::vector<char>& restored,
                            std::function<void(size_t, std::string_view)> arrived,
                            const std::atomic<bool>* cancel) = 0;

    /// Before begin_pass, on the gathering process: item `i` is held already (its bytes and
    /// primary rays), as if rendered here.
    virtual void restored(size_t i, std::string bytes, uint64_t primary_rays) = 0;

    /// The next item to render here, or kNone when this process has no more in this pass.
    /// Any thread.
    virtual size_t next() = 0;

    /// Item `i`, rendered here: its bytes, and the primary rays it traced. Any thread.
    virtual void finished(size_t i, std::string bytes, uint64_t primary_rays) = 0;

    /// Waits for the pass to end; returns the bytes of the items rendered elsewhere that this
    /// process needs (see begin_pass), in no particular order.
    virtual std::vector<std::pair<size_t, std::string>> end_pass() = 0;
};

}  // namespace luz
