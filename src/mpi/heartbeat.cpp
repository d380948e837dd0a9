// Heartbeat: one thread per process, polling every 10 ms: it takes in the others' beats, sends
// its own every beat_ seconds (a tenth of the timeout, at most 1 s), and ends the run when a
// watched process has been silent for the timeout. Goodbyes end it, so that every message sent
// is received before MPI_Finalize.
#include "mpi/heartbeat.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#include "app/cli_main.h"

namespace luz::mpi {
namespace {

using Clock = std::chrono::steady_clock;

constexpr int kTag = 1;
constexpr uint64_t kAlive = 1, kBye = 2;
const uint64_t kAliveMessage = kAlive, kByeMessage = kBye;  // send buffers that outlive sends

/// Rank 0 gives a render that lost a process this long to keep what is done and end the run.
constexpr double kGraceSeconds = 10;

double seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

std::string format_seconds(double s) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", s);
    return text;
}

}  // namespace

double heartbeat_timeout() {
    const char* v = std::getenv("LUZ_MPI_TIMEOUT");
    if (!v) return 60;
    char* end = nullptr;
    const double s = std::strtod(v, &end);
    if (end == v || *end != '\0' || !std::isfinite(s) || s < 0) {
        throw std::invalid_argument(std::string("LUZ_MPI_TIMEOUT=") + v +
                                    ": not a number of seconds (0: never time out)");
    }
    return s;
}

Heartbeat::Heartbeat(MPI_Comm comm, double timeout_seconds) : timeout_(timeout_seconds) {
    MPI_Comm_dup(comm, &comm_);
    MPI_Comm_rank(comm_, &rank_);
    MPI_Comm_size(comm_, &size_);
    beat_ = std::clamp(timeout_ / 10, 0.01, 1.0);
    heard_.assign(static_cast<size_t>(size_), Clock::now());
    gone_.assign(static_cast<size_t>(size_), 0);
    if (timeout_ > 0 && size_ > 1) thread_ = std::thread([this] { run(); });
}

Heartbeat::~Heartbeat() {
    if (thread_.joinable()) {  // not finish()ed: the run is ending otherwise
        finished_ = true;
        thread_.join();
    }
}

void Heartbeat::beat_to(int rank) {
    MPI_Request r;
    MPI_Isend(&kAliveMessage, 1, MPI_UINT64_T, rank, kTag, comm_, &r);
    sends_.push_back(r);
}

void Heartbeat::run() {
    const auto watched = [&](int r) { return rank_ == 0 ? r != 0 : r == 0; };
    // The processes after rank 1 wait 2 s more for a silent rank 0: one message, from rank 1.
    const double limit = timeout_ + (rank_ > 1 ? 2 : 0);
    bool said_bye = false;
    auto next_beat = Clock::now(), last_turn = next_beat;
    while (!finished_) {
        // 1. The beats and goodbyes that came in.
        for (;;) {
            int flag = 0;
            MPI_Status status;
            MPI_Iprobe(MPI_ANY_SOURCE, kTag, comm_, &flag, &status);
            if (!flag) break;
            uint64_t kind = 0;
            MPI_Recv(&kind, 1, MPI_UINT64_T, status.MPI_SOURCE, kTag, comm_, MPI_STATUS_IGNORE);
            heard_[static_cast<size_t>(status.MPI_SOURCE)] = Clock::now();
            if (kind == kBye) gone_[static_cast<size_t>(status.MPI_SOURCE)] = 1;
        }
        const auto now = Clock::now();
        if (seconds(now - last_turn) > 1.0) {
            // This process itself was stopped (or starved): the others' silence meanwhile
            // proves nothing; they get a whole timeout from now.
            std::fill(heard_.begin(), heard_.end(), now);
        }
        last_turn = now;
        // 2. This process's beat (rank 0 to every other, the others to rank 0), or goodbye.
        if (finishing_ && !said_bye) {
            for (int r = 0; r < size_; ++r) {
                if (!watched(r)) continue;
                MPI_Request q;
                MPI_Isend(&kByeMessage, 1, MPI_UINT64_T, r, kTag, comm_, &q);
                sends_.push_back(q);
            }
            said_bye = true;
        } else if (!said_bye && now >= next_beat) {
            for (int r = 0; r < size_; ++r)
                if (watched(r)) beat_to(r);
            next_beat = now + std::chrono::duration_cast<Clock::duration>(
                                  std::chrono::duration<double>(beat_));
        }
        sends_.erase(std::remove_if(sends_.begin(), sends_.end(),
                                    [](MPI_Request& q) {
                                        int done = 0;
                                        MPI_Test(&q, &done, MPI_STATUS_IGNORE);
                                        return done != 0;
                                    }),
                     sends_.end());
        // 3. The watched processes: silent too long, or all gone (after this one's goodbye).
        bool all_gone = true;
        for (int r = 0; r < size_; ++r) {
            if (!watched(r) || gone_[static_cast<size_t>(r)]) continue;
            all_gone = false;
            const double silent = seconds(now - heard_[static_cast<size_t>(r)]);
            if (silent > limit) lost(r, silent);
        }
        if (said_bye && all_gone) break;
        // 4. Rank 0: its render stops on an interruption; a lost process ends the run anyway
        //    once the render has had its time to keep what is done.
        if (rank_ == 0) {
            std::lock_guard lock(mutex_);
            if (interrupt_ && interrupt_->load()) stop_ = true;
            if (lost_ && seconds(now - lost_at_) > kGraceSeconds) {
                if (!reported_) print_error_line("luz: " + *lost_);
                MPI_Abort(MPI_COMM_WORLD, 1);
            }
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    if (said_bye) MPI_Waitall(static_cast<int>(sends_.size()), sends_.data(), MPI_STATUSES_IGNORE);
}

void Heartbeat::lost(int rank, double silent) {
    const std::string n = std::to_string(size_);
    const std::string what =
        (rank_ == 0 ? "process " + std::to_string(rank) + " of " + n
                    : "process " + std::to_string(rank_) + " of " + n + ": process 0 of " + n +
                          " (rank 0)") +
        " has sent nothing for " + format_seconds(silent) +
        " s (stopped, or its machine does not answer): the run ends (LUZ_MPI_TIMEOUT=" +
        format_seconds(timeout_) + ")";
    if (rank_ == 0) {
        std::lock_guard lock(mutex_);
        if (lost_) return;  // being dealt with
        lost_ = what;
        lost_at_ = Clock::now();
        if (rendering_) {  // the render stops, keeps what is done and ends the run
            stop_ = true;
            return;
        }
    }
    print_error_line("luz: " + what);
    MPI_Abort(MPI_COMM_WORLD, 1);
}

const std::atomic<bool>* Heartbeat::begin_render(const std::atomic<bool>* interrupt) {
    if (!thread_.joinable()) return interrupt;
    std::lock_guard lock(mutex_);
    if (lost_) {
        reported_ = true;
        throw std::runtime_error(*lost_);
    }
    rendering_ = true;
    interrupt_ = interrupt;
    stop_ = interrupt && interrupt->load();
    return &stop_;
}

std::optional<std::string> Heartbeat::end_render() {
    std::lock_guard lock(mutex_);
    rendering_ = false;
    interrupt_ = nullptr;
    if (lost_) reported_ = true;
    return lost_;
}

void Heartbeat::finish() {
    if (thread_.joinable()) {
        finishing_ = true;
        thread_.join();
    }
    if (comm_ != MPI_COMM_NULL) MPI_Comm_free(&comm_);
}

}  // namespace luz::mpi
