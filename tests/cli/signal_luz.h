// Test helper: start `luz`, wait until it has reached the step under test, send it a signal,
// and time how long it takes to exit after it (the interrupt tests, `luz figures`).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "cli/run_luz.h"

namespace luz::test {

struct Signalled {
    bool sent = false;     ///< false when luz ended (or the wait ran out) before the signal
    int status = -1;       ///< exit status, 128 + signal when killed by it
    double seconds = 1e9;  ///< from the signal to the exit
    std::string err;       ///< standard error
};

/// Runs LUZ_BINARY `args` in `cwd` (standard input and output /dev/null, standard error kept),
/// in a process group of its own; calls `ready()` every 10 ms until it is true (or luz ended,
/// or `wait_at_most` seconds passed: then no signal is sent), then sends `sig` to luz alone,
/// or to its whole group when `to_group` (what a terminal's Ctrl-C does), and waits for it.
Signalled signal_luz(const std::vector<std::string>& args, const std::filesystem::path& cwd,
                     int sig, const std::function<bool()>& ready, double wait_at_most = 30,
                     bool to_group = false);

/// A `ready` for signal_luz(): true once `seconds` have passed since it was made.
std::function<bool()> after_seconds(double seconds);

/// Whether folder `dir` holds an entry whose name contains `part`.
bool has_entry_containing(const std::filesystem::path& dir, const std::string& part);

}  // namespace luz::test
