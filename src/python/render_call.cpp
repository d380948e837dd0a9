// The render thread and the waiting loop of luz.render().
#include "python/render_call.h"

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>

namespace luz::python {

namespace py = pybind11;

namespace {

/// How often the waiting thread looks at signals and progress.
constexpr std::chrono::milliseconds kPoll{50};

/// What the render thread and the waiting thread share.
struct RenderJob {
    std::atomic<bool> cancel{false};
    std::atomic<double> fraction{0.0};
    std::mutex mutex;
    std::condition_variable done_cv;
    bool done = false;
    Frame frame;
    std::exception_ptr error;
};

}  // namespace

Frame render_interruptibly(const SceneRef& scene, RenderOptions options, py::handle progress) {
    RenderJob job;
    options.control.cancel = &job.cancel;
    // Called by the render's threads: only an atomic store, no Python.
    options.control.progress = [&job](double f) { job.fraction.store(f); };

    bool interrupted = false;  // a Python exception is set (KeyboardInterrupt …)
    double shown = -1;
    {
        py::gil_scoped_release nogil;
        std::thread worker([&] {
            try {
                job.frame = render(scene->scene, scene->desc, options);
            } catch (...) {
                job.error = std::current_exception();
            }
            std::lock_guard lock(job.mutex);
            job.done = true;
            job.done_cv.notify_one();
        });
        std::unique_lock lock(job.mutex);
        while (!job.done_cv.wait_for(lock, kPoll, [&] { return job.done; })) {
            lock.unlock();
            {
                py::gil_scoped_acquire gil;
                if (PyErr_CheckSignals() != 0) {
                    interrupted = true;
                } else if (progress && !progress.is_none()) {
                    const double f = job.fraction.load();
                    if (f > shown) {  // only forward: threads may report out of order
                        shown = f;
                        if (PyObject* r =
                                PyObject_CallOneArg(progress.ptr(), py::float_(f).ptr())) {
                            Py_DECREF(r);
                        } else {
                            interrupted = true;  // the callback raised: stop and raise it
                        }
                    }
                }
            }
            lock.lock();
            if (interrupted) {
                job.cancel.store(true);
                job.done_cv.wait(lock, [&] { return job.done; });
                break;
            }
        }
        lock.unlock();
        worker.join();
    }
    if (interrupted) throw py::error_already_set();
    if (job.error) std::rethrow_exception(job.error);
    return std::move(job.frame);
}

}  // namespace luz::python
