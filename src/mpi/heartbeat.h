// Liveness across luz-mpi's processes (docs/DISTRIBUTED.md): each process's thread sends a small
// message now and then on a communicator of its own; a process silent for LUZ_MPI_TIMEOUT seconds
// (stopped by SIGSTOP, a debugger, a machine that no longer answers) ends the run with a
// message naming it, instead of keeping every other process waiting for ever.
#pragma once

#include <mpi.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace luz::mpi {

/// LUZ_MPI_TIMEOUT in seconds: 60 when unset, 0 for never; throws std::invalid_argument with
/// the message for anything but a number ≥ 0.
double heartbeat_timeout();

class Heartbeat {
  public:
    /// Starts beating and watching (a thread) on a duplicate of `comm` (MPI_THREAD_MULTIPLE):
    /// rank 0 watches every other process, the others watch rank 0. A lost process ends the run
    /// (one line on standard error, MPI_Abort), except on rank 0 during a render (see
    /// begin_render). Every process of `comm` constructs one, together.
    Heartbeat(MPI_Comm comm, double timeout_seconds);
    ~Heartbeat();
    Heartbeat(const Heartbeat&) = delete;
    Heartbeat& operator=(const Heartbeat&) = delete;

    /// Rank 0, before a render: returns the flag the render is to stop on, set once `interrupt`
    /// is set (within 10 ms) or a process is lost. Throws std::runtime_error (the message) when
    /// one is lost already.
    const std::atomic<bool>* begin_render(const std::atomic<bool>* interrupt);

    /// Rank 0, after it: the message naming the lost process, if one was lost during the
    /// render (the caller keeps what is done and ends the run with it within 10 s, after which
    /// the run is ended anyway).
    std::optional<std::string> end_render();

    /// The end of a run that was not aborted (every process calls it): says goodbye, and waits
    /// (still watching) for the others' goodbyes, so that no message is left unreceived.
    void finish();

  private:
    void run();
    void beat_to(int rank);
    void lost(int rank, double silent);

    MPI_Comm comm_ = MPI_COMM_NULL;
    int rank_ = 0, size_ = 1;
    double timeout_ = 0, beat_ = 1;
    std::vector<MPI_Request> sends_;
    std::vector<std::chrono::steady_clock::time_point> heard_;  ///< per rank, its last message
    std::vector<char> gone_;                                    ///< per rank, said goodbye
    std::atomic<bool> finishing_{false}, finished_{false};
    std::atomic<bool> stop_{false};  ///< rank 0's render stops on it
    std::mutex mutex_;               ///< guards what follows
    bool rendering_ = false, reported_ = false;
    const std::atomic<bool>* interrupt_ = nullptr;
    std::optional<std::string> lost_;
    std::chrono::steady_clock::time_point lost_at_;
    std::thread thread_;
};

}  // namespace luz::mpi
