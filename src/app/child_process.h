// Running another program (`luz figures` runs python3) so that Ctrl-C and SIGTERM stop it and
// everything it started within a second, quietly, and this process can clean up afterwards.
#pragma once

#include <string>
#include <vector>

namespace luz {

/// How a child process ended.
struct ChildResult {
    int status = 127;  ///< exit status, 128 + signal when killed, 127 when it could not start
    int stopped = 0;   ///< the signal (SIGINT, SIGTERM) that stopped it from here, or 0
};

/// Runs `argv` (argv[0]: a path) in a process group of its own and waits for it. A SIGINT or
/// SIGTERM to this process (a terminal's Ctrl-C reaches only this process, the group is not in
/// the foreground) ends the group: SIGTERM at once (Python then ends without a traceback),
/// SIGKILL half a second later for what ignores it; it returns once every process the child
/// started has ended (this process adopts them: PR_SET_CHILD_SUBREAPER). The handlers stay
/// installed: a signal that comes later is only recorded (stop_signal()), so that the caller
/// can finish or undo its own work before it exits.
ChildResult run_child(const std::vector<std::string>& argv);

/// The SIGINT or SIGTERM received since run_child() installed its handlers, or 0.
int stop_signal();

}  // namespace luz
