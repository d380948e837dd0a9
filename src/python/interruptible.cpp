// run_interruptibly(): the work's thread, the caller's waiting loop, and the exit hook's protocol:
// once the interpreter is exiting no caller takes the GIL again, and the hook returns only when
// no caller is on its way to take it and every work is joined.
#include "python/interruptible.h"

#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>

#include "luz/errors.h"

namespace luz::python {

namespace py = pybind11;

namespace {

/// How often the waiting thread looks at signals and progress.
constexpr std::chrono::milliseconds kPoll{50};

/// One call's work: its flag and its end.
struct Job {
    std::atomic<bool> cancel{false};
    std::mutex mutex;
    std::condition_variable done_cv;
    bool done = false;
    std::exception_ptr error;

    /// Whether the work ended within `timeout`.
    bool wait_done(std::chrono::milliseconds timeout) {
        std::unique_lock lock(mutex);
        return done_cv.wait_for(lock, timeout, [this] { return done; });
    }
    void wait_done() {
        std::unique_lock lock(mutex);
        done_cv.wait(lock, [this] { return done; });
    }
};

/// What the calls share with the exit hook.
struct Registry {
    std::mutex mutex;
    std::condition_variable changed;
    bool exiting = false;
    std::set<Job*> jobs;  ///< calls whose work is not joined yet
    int taking_gil = 0;   ///< callers past the check of `exiting`, not yet holding the GIL
};

/// Never destroyed: a daemon thread may still wait on it while the process ends.
Registry& registry() {
    static Registry* const r = new Registry;
    return *r;
}

/// What a caller does once the interpreter is exiting: nothing more, until the process ends.
[[noreturn]] void sleep_forever() {
    for (;;) std::this_thread::sleep_for(std::chrono::hours(24));
}

/// Takes the GIL back (`saved`: what PyEval_SaveThread() gave), unless the interpreter is
/// exiting: then returns false without it.
bool take_gil(PyThreadState* saved) {
    Registry& r = registry();
    {
        std::lock_guard lock(r.mutex);
        if (r.exiting) return false;
        ++r.taking_gil;
    }
    PyEval_RestoreThread(saved);
    {
        std::lock_guard lock(r.mutex);
        --r.taking_gil;
    }
    r.changed.notify_all();
    return true;
}

/// Joins the work and says so to the exit hook.
void finish(Job& job, std::thread& worker) {
    if (worker.joinable()) worker.join();
    Registry& r = registry();
    {
        std::lock_guard lock(r.mutex);
        r.jobs.erase(&job);
    }
    r.changed.notify_all();
}

/// The interpreter is exiting: the work is cancelled and joined, and the caller never returns.
[[noreturn]] void end_at_exit(Job& job, std::thread& worker) {
    job.cancel.store(true);
    job.wait_done();
    finish(job, worker);
    sleep_forever();
}

/// Calls `tick` with the GIL; false once a Python exception is set.
bool call_tick(const std::function<bool()>& tick) {
    if (!tick) return true;
    try {
        return tick();
    } catch (py::error_already_set& e) {
        e.restore();
    } catch (const std::exception& e) {
        PyErr_SetString(PyExc_RuntimeError, e.what());
    }
    return false;
}

}  // namespace

void run_interruptibly(const std::function<void(const std::atomic<bool>& cancel)>& work,
                       const std::function<bool()>& tick) {
    Registry& reg = registry();
    Job job;
    {
        std::lock_guard lock(reg.mutex);
        if (reg.exiting) throw std::runtime_error("luz: the interpreter is exiting");
        reg.jobs.insert(&job);
    }
    PyThreadState* saved = PyEval_SaveThread();
    std::thread worker;
    try {
        worker = std::thread([&job, &work] {
            try {
                const CancelScope scope(&job.cancel);
                work(job.cancel);
            } catch (...) {
                job.error = std::current_exception();
            }
            std::lock_guard lock(job.mutex);
            job.done = true;
            job.done_cv.notify_all();
        });
    } catch (...) {  // no thread (out of resources): the error is the call's
        job.error = std::current_exception();
        job.done = true;
    }

    bool raised = false;  // a Python exception is set (KeyboardInterrupt, the tick's)
    while (!job.wait_done(kPoll)) {
        if (!take_gil(saved)) end_at_exit(job, worker);
        raised = PyErr_CheckSignals() != 0 || !call_tick(tick);
        saved = PyEval_SaveThread();
        if (raised) {
            job.cancel.store(true);
            job.wait_done();
            break;
        }
    }
    finish(job, worker);
    if (!take_gil(saved)) sleep_forever();

    if (raised) throw py::error_already_set();
    if (job.error) {
        try {
            std::rethrow_exception(job.error);
        } catch (const Cancelled&) {  // only the exit hook cancels without raising
            throw std::runtime_error("luz: cancelled");
        }
    }
}

void cancel_all_at_exit() {
    Registry& reg = registry();
    PyThreadState* saved = PyEval_SaveThread();
    {
        std::unique_lock lock(reg.mutex);
        reg.exiting = true;
        for (Job* job : reg.jobs) job->cancel.store(true);
        reg.changed.wait(lock, [&reg] { return reg.jobs.empty() && reg.taking_gil == 0; });
    }
    PyEval_RestoreThread(saved);
}

}  // namespace luz::python
