// What rank 0 sends every other process before rendering (docs/DISTRIBUTED.md: only rank 0 reads
// the scene and its files): whether to render at all, and the files the scene loader read.
#pragma once

#include <map>
#include <string>
#include <string_view>

#include "luz_engine.h"  // TextReader

namespace luz::mpi {

struct SceneBundle {
    /// -1: render; otherwise rank 0 stopped before rendering (bad input, --help) and every
    /// process exits with this status, silently (rank 0 has said why).
    int status = -1;
    std::map<std::string, std::string> files;  ///< path as the loader named it → its bytes
};

std::string encode(const SceneBundle& b);
/// Throws WireError when `bytes` is not a whole bundle.
SceneBundle decode_bundle(std::string_view bytes);

/// A file observer (set_file_observer()) that keeps every file the loader read in `into`.
FileObserver recorder(SceneBundle& into);

/// A file source that reads the files of `b` (and refuses the others: rank 0 did not read them).
TextReader bundle_source(const SceneBundle& b);

}  // namespace luz::mpi
