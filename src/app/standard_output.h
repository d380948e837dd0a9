// Standard output of the `luz` command: a reader that goes away (`| head -1`) stops the
// printing, not the work; any other write error is reported once, at the end (exit 1).
#pragma once

namespace luz {

/// Catches SIGPIPE with a handler that does nothing (a program luz starts gets the default
/// back), so that a write to a pipe without a reader fails with EPIPE instead of ending luz.
void catch_sigpipe();

/// Flushes standard output and remembers the first write error.
void flush_standard_output();

/// At the end of a command: flushes standard output; when a write to it failed for any reason
/// but a reader gone away (EPIPE), prints "luz: standard output: cannot write: REASON" and
/// returns 1 (or `status` when that is already a failure); otherwise returns `status`.
int finish_standard_output(int status);

}  // namespace luz
