// Writing an output that is a stream (a device, FIFO, socket or open descriptor): all of its
// bytes, waiting for a reader in short steps that a cancel flag can end; SIGPIPE never kills.
#pragma once

#include <atomic>
#include <string>
#include <string_view>

#include "image/output_target.h"

namespace luz {

/// Writes `bytes` to the stream `target` (Kind::stream: opened, written, closed;
/// Kind::descriptor: written at the descriptor's own offset, after flushing stdout or stderr
/// if it is theirs). A FIFO without a reader and a full pipe are waited for in steps of 50 ms,
/// each checking `cancel` (nullptr: never). Throws FileError naming `label` ("LABEL: cannot
/// write: Broken pipe"; WriteCancelled when cancelled). A reader gone away is EPIPE, never a
/// SIGPIPE that ends the process; on standard output it is no error (the reader stopped
/// reading, as `| head` does: what goes there is dropped, the other outputs are written).
void write_stream(const OutputTarget& target, const std::string& label, std::string_view bytes,
                  const std::atomic<bool>* cancel);

}  // namespace luz
