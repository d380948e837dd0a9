// Interruption of `luz render` (SIGINT, SIGTERM): the handlers only set a lock-free flag, which
// the render loops poll per tile; the command then writes nothing and exits 128 + signal.
#pragma once

#include <atomic>

namespace luz {

/// Installs the SIGINT and SIGTERM handlers (sigaction). While `exit_now` is set (nothing is
/// being written and nothing can be cancelled, e.g. while a scene loads) a signal prints
/// "luz: interrupted" and ends the process at once; otherwise it only sets the flag. A second
/// signal always ends the process at once.
void install_interrupt_handlers();

/// Installs `handler` (async-signal-safe) for SIGINT and SIGTERM, with SA_RESTART: what
/// install_interrupt_handlers() does with luz's own handler.
void install_stop_handler(void (*handler)(int));

/// Chooses between ending at once and only setting the flag (see above).
void set_interrupt_exits_now(bool exit_now);

/// The flag the handlers set; RenderControl::cancel points to it.
const std::atomic<bool>& interrupt_flag();

/// The signal that set the flag (SIGINT, SIGTERM), or 0.
int interrupt_signal();

/// Throws Interrupted when the flag is set.
void throw_if_interrupted();

/// Thrown once the flag is set, where work stops; main() prints "luz: interrupted" and exits
/// with 128 + signal (130 for SIGINT, 143 for SIGTERM).
struct Interrupted {
    int signal;
};

}  // namespace luz
