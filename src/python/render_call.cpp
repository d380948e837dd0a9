// The render of luz.render(), run interruptibly (python/interruptible.h), with its progress.
#include "python/render_call.h"

#include <atomic>

#include "python/interruptible.h"

namespace luz::python {

namespace py = pybind11;

Frame render_interruptibly(const SceneRef& scene, RenderOptions options, py::handle progress) {
    std::atomic<double> fraction{0.0};
    // Called by the render's threads: only an atomic store, no Python.
    options.progress = [&fraction](double f) { fraction.store(f); };
    const bool report = progress && !progress.is_none();
    double shown = -1;
    Frame frame;
    run_interruptibly(
        [&](const std::atomic<bool>& cancel) {
            options.cancel = &cancel;
            frame = render(scene->scene, scene->desc, options);
        },
        [&] {
            const double f = fraction.load();
            if (!report || f <= shown) return true;  // only forward: threads report out of order
            shown = f;
            PyObject* r = PyObject_CallOneArg(progress.ptr(), py::float_(f).ptr());
            Py_XDECREF(r);
            return r != nullptr;  // the callback raised: stop and raise it
        });
    return frame;
}

}  // namespace luz::python
