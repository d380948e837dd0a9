// MpiTileShare: tiles handed out on request by rank 0, their bytes gathered there (and, for a
// pass every process needs, broadcast back). Every MPI call here is made by one thread at a time
// (the heartbeat's thread has a communicator of its own): under mutex_ by the render threads (rank
// 0 serves the others' requests in next(), between two of its tiles, and in end_pass() once its own
// are done), and by the main thread between passes. Waits poll, so that a cancelled render (a
// signal) stops waiting at once.
#include "mpi/mpi_tile_share.h"

#include <algorithm>
#include <chrono>
#include <climits>
#include <thread>

#include "mpi/wire.h"

namespace luz::mpi {
namespace {

constexpr uint64_t kRequest = 1, kFinal = 2;
constexpr int kTagBase = 16;        ///< below: other messages
constexpr int kTagPasses = 100000;  ///< pass numbers wrap (tags stay < 2^18)

/// Sleeps a little longer each time nothing happened (10 µs up to 0.1 ms).
struct Backoff {
    int us = 0;
    void idle() {
        us = std::min(100, us ? us * 2 : 10);
        std::this_thread::sleep_for(std::chrono::microseconds(us));
    }
    void busy() { us = 0; }
};

/// Buffers of broadcasts abandoned by a cancelled wait: the others may still be copying from
/// them (Open MPI's shared memory reads a large message out of the sender's memory), so they
/// stay until the process ends, which it does soon (the run is interrupted). Freed at once, the
/// others' reads would fail and print "Read -1, expected …, errno = 14" after luz's message.
std::vector<std::string>& abandoned_buffers() {
    static std::vector<std::string> buffers;
    return buffers;
}

}  // namespace

MpiTileShare::MpiTileShare(MPI_Comm comm, int pass_base) : comm_(comm), pass_base_(pass_base) {
    MPI_Comm_rank(comm_, &rank_);
    MPI_Comm_size(comm_, &size_);
    rays_.assign(static_cast<size_t>(size_), 0);
    // Pass numbers wrap below the library's largest tag (MPI promises at least 32767).
    int* ub = nullptr;
    int flag = 0;
    MPI_Comm_get_attr(comm_, MPI_TAG_UB, &ub, &flag);
    const int largest = flag && ub ? *ub : 32767;
    tag_passes_ = std::max(2, std::min(kTagPasses, (largest - kTagBase - 1) / 2));
}

size_t MpiTileShare::preassigned(size_t count, int processes) {
    return std::clamp<size_t>(count / (4 * static_cast<size_t>(processes)), 1, 8);
}

int MpiTileShare::work_tag() const { return kTagBase + 2 * ((pass_base_ + pass_) % tag_passes_); }
int MpiTileShare::reply_tag() const { return work_tag() + 1; }

void MpiTileShare::restored(size_t i, std::string bytes, uint64_t primary_rays) {
    rays_[0] += primary_rays;
    restored_.emplace_back(i, std::move(bytes));
}

void MpiTileShare::begin_pass(size_t count, bool everyone, const std::vector<char>& restored,
                              std::function<void(size_t, std::string_view)> arrived,
                              const std::atomic<bool>* cancel) {
    ++pass_;
    stopped_ = stopped_ || (cancel && cancel->load(std::memory_order_relaxed));
    count_ = count;
    everyone_ = everyone;
    arrived_ = std::move(arrived);
    cancel_ = cancel;
    queue_.clear();
    exhausted_ = false;
    mine_.assign(count, 0);
    pending_.clear();
    pending_count_ = 0;
    // What rank 0 holds already (from its checkpoint) is rendered by no one.
    std::vector<char> held = rank_ == 0 ? restored : std::vector<char>(count, 0);
    held.resize(count, 0);
    if (size_ > 1 && !stopped_) {
        MPI_Request r;
        MPI_Ibcast(held.data(), static_cast<int>(count), MPI_CHAR, 0, comm_, &r);
        if (!wait(r)) stopped_ = true;
    }
    if (stopped_) {  // cancelled: this render is over, every pass from now on is empty
        to_render_.clear();
        exhausted_ = true;
        return;
    }
    to_render_.clear();
    for (size_t i = 0; i < count; ++i)
        if (!held[i]) to_render_.push_back(i);
    const size_t n = to_render_.size(), p = preassigned(n, size_);
    for (size_t k = rank_ * p; k < std::min(n, (rank_ + 1) * p); ++k)
        queue_.push_back(to_render_[k]);
    if (rank_ == 0) {
        next_free_ = std::min(n, static_cast<size_t>(size_) * p);
        bytes_.assign(count, {});
        have_.assign(count, 0);
        for (auto& [i, bytes] : restored_) {
            mine_[i] = 1;  // read back here already
            if (everyone_) {
                bytes_[i] = std::move(bytes);
                have_[i] = 1;
            }
        }
        restored_.clear();
        finals_ = 0;
    }
}

bool MpiTileShare::wait(MPI_Request& r) {
    Backoff backoff;
    for (;;) {
        int done = 0;
        MPI_Test(&r, &done, MPI_STATUS_IGNORE);
        if (done) return true;
        if (cancelled()) {
            stopped_ = true;
            return false;
        }
        backoff.idle();
    }
}

std::string MpiTileShare::take_pending(uint64_t kind) {
    std::string message;
    put_u64(message, kind);
    put_u64(message, pending_count_);
    message += pending_;
    pending_.clear();
    pending_count_ = 0;
    if (message.size() > static_cast<size_t>(INT_MAX))
        throw std::runtime_error("mpirun: a message of more than 2 GiB (fewer AOVs or tiles?)");
    return message;
}

void MpiTileShare::send_final() {
    std::string message = take_pending(kFinal);
    MPI_Request r;
    MPI_Isend(message.data(), static_cast<int>(message.size()), MPI_BYTE, 0, work_tag(), comm_, &r);
    wait(r);
}

void MpiTileShare::post_request() {
    request_ = take_pending(kRequest);
    MPI_Isend(request_.data(), static_cast<int>(request_.size()), MPI_BYTE, 0, work_tag(), comm_,
              &send_request_);
    MPI_Irecv(reply_, static_cast<int>(sizeof reply_), MPI_BYTE, 0, reply_tag(), comm_,
              &reply_request_);
    request_out_ = true;
}

bool MpiTileShare::take_reply(bool block) {
    if (!request_out_) return true;
    int done = 0;
    if (block) {
        if (!wait(reply_request_)) return false;
        done = 1;
    } else {
        MPI_Test(&reply_request_, &done, MPI_STATUS_IGNORE);
    }
    if (!done) {
        MPI_Test(&send_request_, &done, MPI_STATUS_IGNORE);  // moves a large request along
        return true;
    }
    if (!wait(send_request_)) return false;  // answered, so received: completes at once
    request_out_ = false;
    const uint64_t n = std::min<uint64_t>(reply_[0], kMaxBatch);
    for (uint64_t k = 0; k < n; ++k)
        if (reply_[1 + k] < count_) queue_.push_back(reply_[1 + k]);
    exhausted_ = n == 0;
    last_batch_ = n;
    return true;
}

size_t MpiTileShare::next() {
    std::lock_guard lock(mutex_);
    if (stopped_ || cancelled()) return kNone;
    if (rank_ == 0) {
        if (size_ > 1) serve();  // the requests that came in meanwhile, between two tiles
        if (queue_.empty()) {
            const size_t k = next_free_.fetch_add(1);
            if (k >= to_render_.size()) return kNone;
            queue_.push_back(to_render_[k]);
        }
    } else {
        // Ask for more before running out (half the last batch left), so that the reply's latency
        // hides behind the work in hand; wait only when nothing is left.
        for (;;) {
            if (!take_reply(false)) return kNone;
            if (!queue_.empty()) {
                const size_t low = std::max(kLowWater, last_batch_ / 2);
                if (queue_.size() <= low + 1 && !request_out_ && !exhausted_) post_request();
                break;
            }
            if (exhausted_ && !request_out_) return kNone;
            if (!request_out_) post_request();
            if (!take_reply(true)) return kNone;
        }
    }
    const size_t i = queue_.front();
    queue_.pop_front();
    mine_[i] = 1;
    return i;
}

void MpiTileShare::finished(size_t i, std::string bytes, uint64_t primary_rays) {
    std::lock_guard lock(mutex_);
    if (rank_ == 0) {
        rays_[0] += primary_rays;
        if (everyone_) {
            bytes_[i] = std::move(bytes);
            have_[i] = 1;
        }
        return;
    }
    put_u64(pending_, i);
    put_u64(pending_, primary_rays);
    put_bytes(pending_, bytes);
    ++pending_count_;
}

void MpiTileShare::take(int from, std::string_view message) {
    WireReader in(message);
    in.u64();  // the kind, read by serve()
    const uint64_t n = in.u64();
    for (uint64_t k = 0; k < n; ++k) {
        const uint64_t item = in.u64(), rays = in.u64();
        const std::string_view bytes = in.bytes();
        if (item >= count_ || have_[item])
            throw WireError("process " + std::to_string(from) + " sent tile " +
                            std::to_string(item) + " of " + std::to_string(count_) + " twice");
        bytes_[item] = std::string(bytes);
        have_[item] = 1;
        rays_[static_cast<size_t>(from)] += rays;
        ++wire_.tiles;
        wire_.tile_bytes += bytes.size();
        if (arrived_) arrived_(item, bytes_[item]);
    }
    if (!in.done()) throw WireError("a message from process " + std::to_string(from) + " is long");
}

void MpiTileShare::serve() {
    std::string message;
    for (;;) {
        int flag = 0;
        MPI_Status status;
        MPI_Message handle;
        MPI_Improbe(MPI_ANY_SOURCE, work_tag(), comm_, &flag, &handle, &status);
        if (!flag) return;
        int n = 0;
        MPI_Get_count(&status, MPI_BYTE, &n);
        message.resize(static_cast<size_t>(n));
        // A large message needs its sender's help to arrive: wait without blocking on it.
        MPI_Request r;
        MPI_Imrecv(message.data(), n, MPI_BYTE, &handle, &r);
        if (!wait(r)) {
            abandoned_buffers().push_back(std::move(message));  // may still be written
            return;
        }
        ++wire_.messages;
        if (message.size() < 8)
            throw WireError("a message from process " + std::to_string(status.MPI_SOURCE) +
                            " is truncated");
        uint64_t kind;
        std::memcpy(&kind, message.data(), sizeof kind);
        take(status.MPI_SOURCE, message);
        if (kind == kFinal) {
            ++finals_;
            continue;
        }
        // A request: a batch shrinking as the pass ends (guided), so the last items spread.
        const size_t total = to_render_.size(), free = next_free_.load();
        const size_t left = free < total ? total - free : 0;
        const size_t batch =
            std::clamp<size_t>(left / (2 * static_cast<size_t>(size_)), 1, kMaxBatch);
        const size_t first = next_free_.fetch_add(batch);
        std::string reply;
        put_u64(reply, 0);
        uint64_t count = 0;
        for (size_t k = first; k < first + batch && k < total; ++k, ++count)
            put_u64(reply, to_render_[k]);
        std::memcpy(reply.data(), &count, sizeof count);
        // Not MPI_Send: a process stopped by a signal no longer takes its replies in, and a
        // blocking send would keep rank 0 from keeping what is done before mpirun kills it.
        MPI_Request sent;
        MPI_Isend(reply.data(), static_cast<int>(reply.size()), MPI_BYTE, status.MPI_SOURCE,
                  reply_tag(), comm_, &sent);
        if (!wait(sent)) {
            abandoned_buffers().push_back(std::move(reply));  // may still be read
            return;
        }
        ++wire_.messages;
    }
}

std::vector<std::pair<size_t, std::string>> MpiTileShare::end_pass() {
    std::vector<std::pair<size_t, std::string>> elsewhere;
    if (stopped_ || cancelled()) {
        stopped_ = true;
        return elsewhere;  // the render is cancelled: what is missing stays missing
    }
    // Every process needs every item: rank 0 broadcasts them all, in chunks below 2 GiB.
    const auto broadcast = [&](std::string& all) -> bool {
        uint64_t size = all.size();
        MPI_Request r;
        MPI_Ibcast(&size, 1, MPI_UINT64_T, 0, comm_, &r);
        if (!wait(r)) return false;
        all.resize(size);
        for (uint64_t at = 0; at < size; at += 1u << 30) {
            const int n = static_cast<int>(std::min<uint64_t>(size - at, 1u << 30));
            MPI_Ibcast(all.data() + at, n, MPI_BYTE, 0, comm_, &r);
            if (!wait(r)) {
                abandoned_buffers().push_back(std::move(all));  // still being read
                return false;
            }
        }
        wire_.broadcast_bytes += size;
        return true;
    };
    if (rank_ == 0) {
        // Rank 0's threads are done: serve the others until each has sent its last tiles.
        Backoff backoff;
        std::lock_guard lock(mutex_);
        while (size_ > 1 && finals_ < size_ - 1 && !cancelled()) {
            const int before = finals_;
            const uint64_t messages = wire_.messages;
            serve();
            if (wire_.messages == messages && finals_ == before) {
                backoff.idle();
            } else {
                backoff.busy();  // more may be on the way: look again soon
            }
        }
        if (cancelled()) return elsewhere;
        if (everyone_ && size_ > 1) {
            std::string all;
            put_u64(all, count_);
            for (size_t i = 0; i < count_; ++i) {
                if (!have_[i])
                    throw std::logic_error("mpirun: a tile is missing at the end of a pass");
                put_u64(all, i);
                put_bytes(all, bytes_[i]);
            }
            if (!broadcast(all)) return elsewhere;
        }
        for (size_t i = 0; i < count_; ++i)
            if (have_[i] && !mine_[i]) elsewhere.emplace_back(i, std::move(bytes_[i]));
        return elsewhere;
    }
    if (cancelled()) return elsewhere;
    send_final();
    if (everyone_) {
        std::string all;
        if (!broadcast(all)) return elsewhere;
        WireReader in(all);
        const uint64_t n = in.u64();
        if (n != count_)
            throw WireError("rank 0 sent " + std::to_string(n) + " tiles, not " +
                            std::to_string(count_));
        for (uint64_t k = 0; k < n; ++k) {
            const uint64_t item = in.u64();
            const std::string_view bytes = in.bytes();
            if (item < count_ && !mine_[item]) elsewhere.emplace_back(item, std::string(bytes));
        }
    }
    return elsewhere;
}

}  // namespace luz::mpi
