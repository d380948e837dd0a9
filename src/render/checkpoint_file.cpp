// The checkpoint file, every number little-endian 64-bit: the header ("LUZCKPT\0", version,
// key, item count, crc32 of those 32 bytes), each finished tile (index, size, crc32 of index,
// size and bytes; its bytes), then the end (~0, number of tiles, crc32 of the header and of
// every tile's 24 leading bytes).
#include "render/checkpoint_file.h"

#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cstring>

#include "scene/input_error.h"

namespace luz {

namespace {

constexpr char kMagic[8] = {'L', 'U', 'Z', 'C', 'K', 'P', 'T', '\0'};
constexpr uint64_t kEnd = ~uint64_t{0};
constexpr size_t kHeader = 40, kTileHead = 24, kEndSize = 24;

void put64(std::string& out, uint64_t v) {
    char b[8];
    for (int k = 0; k < 8; ++k) b[k] = static_cast<char>((v >> (8 * k)) & 0xff);
    out.append(b, 8);
}

uint64_t get64(std::string_view bytes, size_t at) {
    uint64_t v = 0;
    for (int k = 0; k < 8; ++k) v |= uint64_t(static_cast<unsigned char>(bytes[at + k])) << (8 * k);
    return v;
}

uint32_t crc(uint32_t running, std::string_view bytes) {
    // zlib's crc32 takes at most 4 GiB at a time (uInt)
    while (!bytes.empty()) {
        const size_t n = std::min<size_t>(bytes.size(), 1u << 30);
        running = static_cast<uint32_t>(
            crc32(running, reinterpret_cast<const Bytef*>(bytes.data()), static_cast<uInt>(n)));
        bytes.remove_prefix(n);
    }
    return running;
}

std::string tile_head(uint64_t index, uint64_t size) {
    std::string head;
    put64(head, index);
    put64(head, size);
    return head;
}

}  // namespace

bool may_be_checkpoint(std::string_view first) {
    if (first.size() < 8)
        return first.empty() || std::memcmp(first.data(), kMagic, first.size()) == 0;
    int distance = 0;
    for (size_t k = 0; k < 8; ++k) {
        const auto c = static_cast<unsigned char>(first[k] ^ kMagic[k]);
        distance += std::popcount(static_cast<unsigned>(c));
    }
    return distance <= 3;
}

uint32_t tile_checksum(uint64_t index, std::string_view bytes) {
    return crc(crc(0, tile_head(index, bytes.size())), bytes);
}

std::vector<std::string_view> checkpoint_pieces(uint64_t key, uint64_t count,
                                                const std::vector<CheckpointTileRef>& tiles,
                                                std::string& heads) {
    heads.clear();
    heads.reserve(kHeader + kTileHead * tiles.size() + kEndSize);  // views into it stay valid
    heads.append(kMagic, 8);
    put64(heads, kCheckpointVersion);
    put64(heads, key);
    put64(heads, count);
    put64(heads, crc(0, heads));
    for (const CheckpointTileRef& t : tiles) {
        put64(heads, t.index);
        put64(heads, t.bytes.size());
        put64(heads, t.crc);
    }
    const uint32_t all = crc(0, heads);  // the header and every tile's head
    put64(heads, kEnd);
    put64(heads, tiles.size());
    put64(heads, all);
    std::vector<std::string_view> pieces;
    pieces.reserve(2 * tiles.size() + 2);
    const std::string_view h = heads;
    pieces.push_back(h.substr(0, kHeader));
    for (size_t k = 0; k < tiles.size(); ++k) {
        pieces.push_back(h.substr(kHeader + kTileHead * k, kTileHead));
        pieces.push_back(tiles[k].bytes);
    }
    pieces.push_back(h.substr(kHeader + kTileHead * tiles.size()));
    return pieces;
}

CheckpointContents parse_checkpoint(std::string_view bytes, uint64_t key, const std::string& path,
                                    bool verify_checksums) {
    const auto bad = [&](const std::string& what) {
        return InputError(path + ": --checkpoint: " + what);
    };
    const auto damaged = [&](const std::string& what) {
        return bad("damaged checkpoint (" + what + ")");
    };
    const auto truncated = [&] {
        return damaged("truncated: " + std::to_string(bytes.size()) + " bytes, its end missing");
    };
    // 1. The magic: a few bits away from it is a damaged checkpoint, not another kind of file.
    if (!may_be_checkpoint(bytes.substr(0, 8))) throw bad("not a luz checkpoint");
    if (bytes.size() < 8) throw truncated();
    if (std::memcmp(bytes.data(), kMagic, 8) != 0) throw damaged("its first bytes are not LUZCKPT");
    // 2. The header: its checksum before any number in it is believed.
    if (bytes.size() < kHeader) throw truncated();
    const uint64_t version = get64(bytes, 8);
    const bool header_ok = get64(bytes, 32) == crc(0, bytes.substr(0, 32));
    if (version == 1 || (header_ok && version != kCheckpointVersion)) {
        throw bad("checkpoint of version " + std::to_string(version) + ", this luz writes " +
                  std::to_string(kCheckpointVersion) +
                  " (render again without it, or remove the file)");
    }
    if (verify_checksums && !header_ok) throw damaged("its header does not match its checksum");
    if (get64(bytes, 16) != key) {
        throw bad(
            "made for another scene or other options (render again without it, or "
            "remove the file)");
    }
    CheckpointContents out;
    out.count = get64(bytes, 24);
    // 3. The tiles, each checked against its checksum and the count; their heads summed.
    uint32_t all = crc(0, bytes.substr(0, kHeader));
    size_t at = kHeader;
    for (;;) {
        if (bytes.size() - at < 8) throw truncated();
        const uint64_t index = get64(bytes, at);
        if (index == kEnd) break;
        const std::string where = "the tile at byte " + std::to_string(at);
        if (index >= out.count) {
            throw damaged(where + " is number " + std::to_string(index) + ", of " +
                          std::to_string(out.count));
        }
        if (bytes.size() - at < kTileHead) throw truncated();
        const uint64_t size = get64(bytes, at + 8);
        const uint64_t stored = get64(bytes, at + 16);
        if (size > bytes.size() - at - kTileHead) {
            throw damaged(where + " has " + std::to_string(size) + " bytes, past the file's end");
        }
        const std::string_view tile = bytes.substr(at + kTileHead, size);
        if (verify_checksums && stored != tile_checksum(index, tile))
            throw damaged(where + " does not match its checksum");
        all = crc(all, bytes.substr(at, kTileHead));
        out.tiles.push_back({index, at + kTileHead, size, static_cast<uint32_t>(stored)});
        at += kTileHead + size;
    }
    // 4. The end: the number of tiles and the checksum of every head, then nothing.
    if (bytes.size() - at < kEndSize) throw truncated();
    if (get64(bytes, at + 8) != out.tiles.size()) {
        throw damaged("its end counts " + std::to_string(get64(bytes, at + 8)) +
                      " tiles, it holds " + std::to_string(out.tiles.size()));
    }
    if (verify_checksums && get64(bytes, at + 16) != all)
        throw damaged("its end does not match its checksum");
    at += kEndSize;
    if (at != bytes.size()) throw damaged("bytes after its end");
    std::sort(out.tiles.begin(), out.tiles.end(),
              [](const CheckpointTile& a, const CheckpointTile& b) { return a.index < b.index; });
    for (size_t k = 1; k < out.tiles.size(); ++k) {
        if (out.tiles[k].index == out.tiles[k - 1].index)
            throw damaged("tile " + std::to_string(out.tiles[k].index) + " twice");
    }
    return out;
}

}  // namespace luz
