// --checkpoint FILE: the file read and checked before any work (render/checkpoint_file.h for its
// bytes), the finished items kept as they come and written every interval() and when asked.
#include "render/checkpoint.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "image/atomic_file.h"
#include "scene/input_error.h"

namespace luz {

namespace {

/// Reads up to `n` bytes of `fd` into `out` (appended); false on a read error (errno set).
bool read_up_to(int fd, size_t n, std::string& out) {
    const size_t start = out.size();
    out.resize(start + n);
    size_t got = 0;
    while (got < n) {
        const ssize_t r = ::read(fd, out.data() + start + got, n - got);
        if (r < 0 && errno == EINTR) continue;
        if (r < 0) return false;
        if (r == 0) break;
        got += static_cast<size_t>(r);
    }
    out.resize(start + got);
    return true;
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

double Checkpoint::interval() {
    if (const char* v = std::getenv("LUZ_CHECKPOINT_SECONDS")) {
        char* end = nullptr;
        const double s = std::strtod(v, &end);
        if (end != v && *end == '\0' && s > 0 && s < 1e9) return s;
    }
    return 10.0;
}

Checkpoint::Checkpoint(std::string path, uint64_t key)
    : path_(std::move(path)),
      key_(key),
      last_save_(std::chrono::steady_clock::now()),
      interval_(interval()) {
    // A save cut short by SIGKILL (mpirun's, one second after its SIGTERM) left its temporary
    // file: the file itself is the last whole save, the temporary file is only in the way.
    remove_stale_temporaries(path_);
    const auto bad = [&](const std::string& what) {
        return InputError(path_ + ": --checkpoint: " + what);
    };
    // Not blocking: a FIFO is refused, not waited for.
    const int fd = ::open(path_.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        if (errno == ENOENT) return;  // a new render
        throw bad(std::string("cannot read: ") + std::strerror(errno));
    }
    struct Closer {
        int fd;
        ~Closer() { ::close(fd); }
    } closer{fd};
    struct stat st {};
    if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) throw bad("not a regular file");
    // Its first bytes, then the rest as `stat` says: a file of another kind is not read whole,
    // and a file that grows while read (or /proc's, of size 0) is refused, not read forever.
    const auto size = static_cast<size_t>(st.st_size);
    if (!read_up_to(fd, std::min<size_t>(size, 8), file_))
        throw bad(std::string("cannot read: ") + std::strerror(errno));
    if (!may_be_checkpoint(file_)) throw bad("not a luz checkpoint");
    if (!read_up_to(fd, size - file_.size() + 1, file_))
        throw bad(std::string("cannot read: ") + std::strerror(errno));
    if (file_.size() > size) throw bad("cannot read: it changed while it was read");
    contents_ = parse_checkpoint(file_, key_, path_);
    loaded_ = true;
}

void Checkpoint::start(size_t items) {
    std::lock_guard lock(mutex_);
    if (started_) {
        if (items_.size() != items) {
            throw InputError(path_ + ": --checkpoint: made for another scene or other options (" +
                             std::to_string(items_.size()) + " tiles, this render has " +
                             std::to_string(items) + ")");
        }
        return;
    }
    // The file's count checked against the render's own before anything is allocated for it
    // (0: saved before the render knew its tiles).
    if (loaded_ && contents_.count != items && contents_.count != 0) {
        throw InputError(path_ + ": --checkpoint: damaged checkpoint (it holds " +
                         std::to_string(contents_.count) + " tiles, this render has " +
                         std::to_string(items) + ")");
    }
    started_ = true;
    items_.resize(items);
    for (const CheckpointTile& t : contents_.tiles) {
        Item& item = items_[t.index];
        item.done = true;
        item.crc = t.crc;
        item.bytes.assign(file_, t.offset, t.size);
    }
    contents_ = {};
    std::string().swap(file_);
}

std::string Checkpoint::finish(size_t i, std::string bytes) {
    const uint32_t crc = tile_checksum(i, bytes);  // outside the lock: the threads in parallel
    std::lock_guard lock(mutex_);
    items_[i].done = true;
    items_[i].crc = crc;
    items_[i].bytes = std::move(bytes);
    const auto now = std::chrono::steady_clock::now();
    if (std::chrono::duration<double>(now - last_save_).count() < interval_) return {};
    try {
        save_locked();
    } catch (const FileError& e) {
        last_save_ = now;  // tried again an interval later, not at every tile
        if (warned_) return {};
        warned_ = true;
        char every[32];
        std::snprintf(every, sizeof every, "%g", interval_);
        return std::string(e.what()) +
               " (--checkpoint not saved; the render goes on, trying again every " + every + " s)";
    }
    return {};
}

void Checkpoint::save() {
    std::lock_guard lock(mutex_);
    save_locked();
}

void Checkpoint::save_locked() {
    if (!started_ && loaded_) return;  // stopped before the render began: the file holds it all
    // The heads are gathered first, then written with each item's bytes from where they are: a
    // checkpoint of 100 MB is not copied first (an interrupted run may have a second).
    std::vector<CheckpointTileRef> tiles;
    for (size_t i = 0; i < items_.size(); ++i) {
        if (items_[i].done) tiles.push_back({i, items_[i].crc, items_[i].bytes});
    }
    std::string heads;
    const std::vector<std::string_view> pieces =
        checkpoint_pieces(key_, items_.size(), tiles, heads);
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
