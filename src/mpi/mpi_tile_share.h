// TileShare over MPI (docs/DISTRIBUTED.md), like OSPRay's MPI offload mode: each process starts
// with a few items of the pass given out in advance, then asks rank 0 for more before it runs out;
// rank 0 renders too, answers the requests between two of its tiles (no thread of its own to
// wake) and gathers every item's bytes.
#pragma once

#include <mpi.h>

#include <atomic>
#include <cstdint>
#include <deque>
#include <functional>
#include <mutex>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "luz_engine.h"  // TileShare

namespace luz::mpi {

/// Bytes sent in one render, by kind (docs/SCALING.md).
struct WireCounts {
    uint64_t messages = 0;    ///< requests, replies and finals (rank 0's view)
    uint64_t tile_bytes = 0;  ///< tile payload received by rank 0
    uint64_t tiles = 0;       ///< tiles received by rank 0
    uint64_t broadcast_bytes = 0;
};

class MpiTileShare final : public TileShare {
  public:
    /// One per frame render on every process of `comm`. `pass_base` numbers this render's
    /// passes (their message tags) apart from the previous render's.
    MpiTileShare(MPI_Comm comm, int pass_base);

    void begin_pass(size_t count, bool everyone, const std::vector<char>& restored,
                    std::function<void(size_t, std::string_view)> arrived,
                    const std::atomic<bool>* cancel) override;
    void restored(size_t i, std::string bytes, uint64_t primary_rays) override;
    size_t next() override;
    void finished(size_t i, std::string bytes, uint64_t primary_rays) override;
    std::vector<std::pair<size_t, std::string>> end_pass() override;

    /// Rank 0: the primary rays each process traced in this render so far.
    const std::vector<uint64_t>& primary_rays_by_process() const { return rays_; }
    const WireCounts& wire() const { return wire_; }
    /// The passes this render used (the next render's pass_base starts after them).
    int passes() const { return pass_; }

    /// Items each process is given before it asks (the same on every process).
    static size_t preassigned(size_t count, int processes);
    /// Most items in one reply (tiles may take only tens of µs: a reply must bring many).
    static constexpr size_t kMaxBatch = 256;
    /// A worker asks for more when half its last batch, and at least this many, are left.
    static constexpr size_t kLowWater = 8;

  private:
    bool cancelled() const { return cancel_ && cancel_->load(std::memory_order_relaxed); }
    int work_tag() const;
    int reply_tag() const;
    void serve();  // rank 0: answers and takes in what has arrived, without waiting
    void take(int from, std::string_view message);
    bool wait(MPI_Request& r);                // false when cancelled first
    std::string take_pending(uint64_t kind);  // workers: a message with the finished tiles
    void send_final();                        // workers: the pass's last tiles, waited for
    void post_request();          // workers: a request (with the pending tiles), not waited for
    bool take_reply(bool block);  // workers: the reply to it, if here (or waited for)

    MPI_Comm comm_;
    int rank_ = 0, size_ = 1;
    int pass_base_ = 0, pass_ = -1;
    size_t count_ = 0;
    bool everyone_ = false;
    std::function<void(size_t, std::string_view)> arrived_;
    const std::atomic<bool>* cancel_ = nullptr;

    std::mutex mutex_;
    std::vector<size_t>
        to_render_;  ///< the pass's items not restored, in order: what is handed out
    std::vector<std::pair<size_t, std::string>> restored_;  ///< rank 0, before begin_pass
    std::deque<size_t> queue_;  ///< items given to this process, not yet started
    bool exhausted_ = false;    ///< rank 0 has no more for this process
    std::vector<char> mine_;    ///< items rendered here
    std::string pending_;       ///< finished items not yet sent (workers)
    uint64_t pending_count_ = 0;
    bool request_out_ = false;  ///< a request is out, its reply not taken
    size_t last_batch_ = 0;     ///< items in the last reply
    std::string request_;       ///< its bytes (until sent)
    MPI_Request send_request_ = MPI_REQUEST_NULL, reply_request_ = MPI_REQUEST_NULL;
    uint64_t reply_[1 + kMaxBatch] = {};

    // rank 0
    std::atomic<size_t> next_free_{0};  ///< first position of to_render_ not given out
    std::vector<std::string> bytes_;    ///< per item, when this process keeps it
    std::vector<char> have_;
    std::vector<uint64_t> rays_;
    int finals_ = 0;
    int tag_passes_ = 2;    ///< pass numbers wrap at this (MPI_TAG_UB)
    bool stopped_ = false;  ///< cancelled: every later pass of this render is empty  ///< workers
                            ///< whose last tiles have come in, this pass
    WireCounts wire_;
};

}  // namespace luz::mpi
