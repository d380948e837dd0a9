// Long C++ work called from Python (load, render, save): run on a thread of its own with the GIL
// released, while the calling thread answers Ctrl-C (KeyboardInterrupt); the interpreter's exit
// cancels and joins every such work, whichever thread called it.
#pragma once

#include <pybind11/pybind11.h>

#include <atomic>
#include <functional>

namespace luz::python {

/// Runs `work(cancel)` on a thread of its own, with `cancel` as its CancelScope (loaders,
/// builders and encoders stop at their next check once it is set; a render is given it as
/// RenderControl::cancel) and the GIL released. The calling thread waits; every ~50 ms it takes
/// the GIL, checks for signals and calls `tick` (if any), which returns false with a Python
/// exception set to stop. On a Python exception (KeyboardInterrupt …) `cancel` is set, the work
/// joined and the exception raised; `work`'s own exceptions are rethrown. Call with the GIL.
///
/// At interpreter exit (cancel_all_at_exit()) the work is cancelled and joined, and a caller
/// still waiting — a daemon thread — never takes the GIL again: it sleeps until the process
/// ends, as Python 3.14 does with such threads, instead of being ended by pthread_exit() on the
/// way back (which aborts a C++ frame: "terminate called without an active exception").
void run_interruptibly(const std::function<void(const std::atomic<bool>& cancel)>& work,
                       const std::function<bool()>& tick = {});

/// The module's atexit hook (runs before the interpreter finalizes, with the GIL): cancels
/// every run_interruptibly() under way and waits, with the GIL released, until each has joined
/// its work. Later calls raise RuntimeError.
void cancel_all_at_exit();

}  // namespace luz::python
