// Reading the loader's input files (the scene, OBJ and MTL files): regular files only, read
// with a size bound; where they come from (disk, or rank 0 under mpirun); the memory limit.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

namespace luz {

/// Reads the file at `path` whole; on failure returns nullopt and sets `reason` (e.g. "No such
/// file or directory").
using TextReader =
    std::function<std::optional<std::string>(const std::string& path, std::string& reason)>;

/// Reads a file through the file source (below; the default TextReader): from disk, refusing
/// at once what is not a regular file (a folder, /dev/zero, a FIFO, a socket), and a file larger
/// than max_text_file_bytes(), whatever its size says (/proc files say 0).
std::optional<std::string> read_text_file(const std::string& path, std::string& reason);

/// read_text_file() from disk, whatever the file source.
std::optional<std::string> read_text_file_from_disk(const std::string& path, std::string& reason);

/// Where the loader reads every file it reads — the scene file, OBJ and MTL files: from disk
/// (an empty source, the default) or from `source`: under mpirun, the other processes read
/// the bytes rank 0 sent (src/mpi/). Process-wide:
/// set it before loading, from one thread.
void set_file_source(TextReader source);
const TextReader& file_source();

/// Called with every file the loader has read from disk (the scene file, OBJ and MTL files),
/// as it was read: rank 0 under mpirun keeps them to send (src/mpi/). Empty: none.
using FileObserver = std::function<void(const std::string& path, const std::string& text)>;
void set_file_observer(FileObserver observer);
const FileObserver& file_observer();

/// The memory a load may use (`luz render` sets --max-memory; default: no limit): a scene, OBJ
/// or MTL file may have a quarter of it (max_text_file_bytes()), and a scene's parsed JSON is
/// refused as soon as it would need more (scene/json_text.h).
void set_memory_limit(uint64_t bytes);
uint64_t memory_limit();

/// The largest scene, OBJ or MTL file read_text_file() reads: a quarter of memory_limit().
uint64_t max_text_file_bytes();

}  // namespace luz
