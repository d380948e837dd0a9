// The checkpoint file: "LUZCKPT" + version, the render's key, the item count, then each
// finished item (index, size, bytes) and an end marker; every number little-endian 64-bit.
#include "render/checkpoint.h"

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "image/atomic_file.h"
#include "scene/input_error.h"

namespace luz {

namespace {

constexpr char kMagic[8] = {'L', 'U', 'Z', 'C', 'K', 'P', 'T', '\0'};
constexpr uint64_t kVersion = 1;
constexpr uint64_t kEnd = ~uint64_t{0};

void put64(std::string& out, uint64_t v) {
    char b[8];
    for (int k = 0; k < 8; ++k) b[k] = static_cast<char>((v >> (8 * k)) & 0xff);
    out.append(b, 8);
}

}  // namespace

uint64_t fingerprint(std::string_view text) {
    uint64_t h = 0xcbf29ce484222325ull;
    for (unsigned char c : text) {
        h ^= c;
        h *= 0x100000001b3ull;
    }
    return h;
}

Checkpoint::Checkpoint(std::string path, uint64_t key)
    : path_(std::move(path)), key_(key), last_save_(std::chrono::steady_clock::now()) {
    // A save cut short by SIGKILL (mpirun's, one second after its SIGTERM) left its temporary
    // file: the file itself is the last whole save, the temporary file is only in the way.
    remove_stale_temporaries(path_);
    std::error_code ec;
    if (!std::filesystem::exists(path_, ec)) return;  // a new render
    const auto bad = [&](const std::string& what) {
        return InputError(path_ + ": --checkpoint: " + what);
    };
    if (!std::filesystem::is_regular_file(path_, ec)) throw bad("not a regular file");
    std::ifstream in(path_, std::ios::binary);
    std::stringstream buf;
    buf << in.rdbuf();
    const std::string bytes = buf.str();
    size_t at = 0;
    const auto get64 = [&](uint64_t& v) {
        if (bytes.size() - at < 8) throw bad("truncated or damaged checkpoint");
        v = 0;
        for (int k = 0; k < 8; ++k)
            v |= uint64_t(static_cast<unsigned char>(bytes[at + k])) << (8 * k);
        at += 8;
    };
    if (bytes.size() < 8 || std::memcmp(bytes.data(), kMagic, 8) != 0) {
        throw bad("not a luz checkpoint");
    }
    at = 8;
    uint64_t version, file_key, count;
    get64(version);
    if (version != kVersion) {
        throw bad("checkpoint of version " + std::to_string(version) + ", this luz writes " +
                  std::to_string(kVersion));
    }
    get64(file_key);
    get64(count);
    if (file_key != key_ || count > (uint64_t{1} << 32)) {
        throw bad(
            "made for another scene or other options (render again without it, or "
            "remove the file)");
    }
    items_.resize(count);
    for (;;) {
        uint64_t i, size;
        get64(i);
        if (i == kEnd) break;
        get64(size);
        if (i >= items_.size() || size > bytes.size() - at)
            throw bad("truncated or damaged checkpoint");
        items_[i].done = true;
        items_[i].bytes.assign(bytes, at, size);
        at += size;
    }
    if (at != bytes.size()) throw bad("damaged checkpoint (bytes after its end)");
}

void Checkpoint::start(size_t items) {
    std::lock_guard lock(mutex_);
    if (items_.empty()) {
        items_.resize(items);
    } else if (items_.size() != items) {
        throw InputError(path_ + ": --checkpoint: made for another scene or other options (" +
                         std::to_string(items_.size()) + " tiles, this render has " +
                         std::to_string(items) + ")");
    }
}

void Checkpoint::finish(size_t i, std::string bytes) {
    std::lock_guard lock(mutex_);
    items_[i].done = true;
    items_[i].bytes = std::move(bytes);
    const auto now = std::chrono::steady_clock::now();
    if (std::chrono::duration<double>(now - last_save_).count() >= kInterval) save_locked();
}

void Checkpoint::save() {
    std::lock_guard lock(mutex_);
    save_locked();
}

void Checkpoint::save_locked() {
    // The numbers are gathered first, then written with each item's bytes from where they
    // are: a checkpoint of 100 MB is not copied first (an interrupted run may have a second).
    std::string head(kMagic, 8), sizes, end;
    put64(head, kVersion);
    put64(head, key_);
    put64(head, items_.size());
    for (size_t i = 0; i < items_.size(); ++i) {
        if (!items_[i].done) continue;
        put64(sizes, i);
        put64(sizes, items_[i].bytes.size());
    }
    put64(end, kEnd);
    std::vector<std::string_view> pieces = {head};
    size_t at = 0;  // in `sizes`: 16 bytes (index, size) before each finished item's bytes
    for (const Item& item : items_) {
        if (!item.done) continue;
        pieces.push_back(std::string_view(sizes).substr(at, 16));
        pieces.push_back(item.bytes);
        at += 16;
    }
    pieces.push_back(end);
    PendingFile file(path_, pieces, Durability::disk);  // it must outlive a machine crash
    file.commit();
    last_save_ = std::chrono::steady_clock::now();
}

void Checkpoint::remove() {
    std::error_code ec;
    std::filesystem::remove(path_, ec);
}

size_t Checkpoint::finished() const {
    std::lock_guard lock(mutex_);
    size_t n = 0;
    for (const Item& it : items_) n += it.done;
    return n;
}

}  // namespace luz
