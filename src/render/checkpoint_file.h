// The bytes of a --checkpoint file (render/checkpoint.h), format version 2: a header, each
// finished tile with a checksum (zlib's crc32), an end record; read without trusting any count,
// index or size it holds before its checksum and the file's own size have vouched for it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace luz {

/// The format this luz writes (version 1 had no checksums).
inline constexpr uint64_t kCheckpointVersion = 2;

/// A finished tile as written: its item number, its bytes and their checksum (tile_checksum).
struct CheckpointTileRef {
    uint64_t index = 0;
    uint32_t crc = 0;
    std::string_view bytes;
};

/// A finished tile found in a file: its item number, where its bytes are, their checksum.
struct CheckpointTile {
    uint64_t index = 0;
    size_t offset = 0, size = 0;
    uint32_t crc = 0;
};

/// What a file holds: the number of items of the render it was made for and its finished
/// tiles, by increasing index (each at most once, each index below `count`).
struct CheckpointContents {
    uint64_t count = 0;
    std::vector<CheckpointTile> tiles;
};

/// The checksum of tile `index` with `bytes` (crc32 of its index, its size and its bytes).
uint32_t tile_checksum(uint64_t index, std::string_view bytes);

/// The file's bytes for a render keyed `key` of `count` items holding `tiles`, as pieces to be
/// written one after the other: the tiles' bytes are not copied; `heads` keeps the others.
std::vector<std::string_view> checkpoint_pieces(uint64_t key, uint64_t count,
                                                const std::vector<CheckpointTileRef>& tiles,
                                                std::string& heads);

/// Whether a file beginning with `first` (its first 8 bytes, or all of a shorter file) may be a
/// checkpoint, damaged or not: a file that may not is refused before it is read further.
bool may_be_checkpoint(std::string_view first);

/// Reads a file's `bytes` for a render keyed `key`; throws InputError "PATH: --checkpoint: …"
/// when they are not a luz checkpoint, of another version, made for another render, or damaged
/// in any way (every message for damage begins with "damaged checkpoint"). Allocates at most in
/// proportion to bytes.size(). `verify_checksums` false is only for the fuzzer (fuzz/), which
/// then reaches the checks behind the checksums.
CheckpointContents parse_checkpoint(std::string_view bytes, uint64_t key, const std::string& path,
                                    bool verify_checksums = true);

}  // namespace luz
