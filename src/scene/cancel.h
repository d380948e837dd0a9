// Cooperative cancellation of long loads, builds and encodings: the thread doing the work holds
// a flag (CancelScope) that another thread or a signal handler may set, and long loops call
// check_cancel(), which throws Cancelled once it is set (a render uses RenderControl::cancel).
#pragma once

#include <atomic>

#include "luz/errors.h"  // Cancelled, CancelScope

namespace luz {

/// The calling thread's cancel flag, or nullptr: to hand to the worker threads of a parallel
/// loop, which check it with cancel_requested().
const std::atomic<bool>* cancel_flag();

/// True once `flag` (may be nullptr) is set.
inline bool cancel_requested(const std::atomic<bool>* flag) {
    return flag != nullptr && flag->load(std::memory_order_relaxed);
}

/// Throws Cancelled when the calling thread's flag is set (one atomic load otherwise).
void check_cancel();

}  // namespace luz
