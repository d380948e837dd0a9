// Wavefront OBJ and MTL input (SPEC §2 `mesh`): tinyobjloader parses and triangulates, after a
// light pass of our own that checks every number and index and names FILE:LINE on bad input.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "scene/input_error.h"
#include "scene/mesh_data.h"

namespace luz {

/// Reads the file at `path` whole; on failure returns nullopt and sets `reason` (e.g. "No such
/// file or directory").
using TextReader =
    std::function<std::optional<std::string>(const std::string& path, std::string& reason)>;

/// Reads a file through the file source (below; the default TextReader): from disk, refusing
/// what is not a regular file (a folder, /dev/zero, a pipe) and a file larger than
/// set_max_text_file_bytes(), before reading.
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

/// The largest OBJ or MTL file read_text_file() reads (default: no limit); `luz render` sets a
/// share of --max-memory, so that a mesh too large is refused rather than half-loaded.
void set_max_text_file_bytes(uint64_t bytes);

/// Parses the OBJ text of `file` (`file` labels messages and locates MTL files: `mtllib` names
/// are relative to its folder; `read` reads them). Polygons are triangulated; `v`, `vn`, `f`,
/// `usemtl` and `mtllib` are used, other statements ignored. With `with_materials` false the MTL
/// files are not read and every face has material −1.
///
/// MTL mapping (SPEC §2): Ka, Kd, Ks → ka, kd, ks (clamped to [0, 1]); Ns → n (Ns ≤ 0 → 1);
/// Ni → ior (below 1 → 1); d → transparency = 1 − d, or Tr → transparency = Tr (d wins);
/// illum 3–7 → reflection = mean of Ks. Keys a material omits keep the default material's.
///
/// Throws InputError "FILE:LINE: what" on a malformed number, a non-finite coordinate, a bad
/// or out-of-range index, or a face with fewer than 3 vertices (MTL errors name the MTL file).
/// A missing MTL file, an unknown `usemtl` name, a clamped MTL value and a file without faces
/// are warnings ("FILE:LINE: what"), appended to `warnings`.
MeshData parse_obj(std::string_view text, const std::string& file, bool with_materials,
                   const TextReader& read, std::vector<std::string>& warnings);

/// Reads and parses the OBJ file at `path` (and its MTL files) from disk. A missing or
/// unreadable OBJ file throws InputError "PATH: cannot read: reason".
MeshData load_obj(const std::string& path, bool with_materials, std::vector<std::string>& warnings);

}  // namespace luz
