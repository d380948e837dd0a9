// The scene bundle: encoding, and the file sources that record it (rank 0) and read it (others).
#include "mpi/scene_bundle.h"

#include "mpi/wire.h"

namespace luz::mpi {

namespace {
constexpr uint64_t kMagic = 0x31424e55424c5a4cull;  // "LZLBUNB1": luz scene bundle, version 1
}

std::string encode(const SceneBundle& b) {
    std::string out;
    put_u64(out, kMagic);
    put_u64(out, static_cast<uint64_t>(static_cast<int64_t>(b.status)));
    put_u64(out, b.files.size());
    for (const auto& [path, text] : b.files) {
        put_bytes(out, path);
        put_bytes(out, text);
    }
    return out;
}

SceneBundle decode_bundle(std::string_view bytes) {
    WireReader in(bytes);
    if (in.u64() != kMagic) throw WireError("it is not a luz scene bundle of this version");
    SceneBundle b;
    b.status = static_cast<int>(static_cast<int64_t>(in.u64()));
    const uint64_t n = in.u64();
    for (uint64_t i = 0; i < n; ++i) {
        const std::string path(in.bytes());
        b.files[path] = std::string(in.bytes());
    }
    if (!in.done()) throw WireError("it has bytes past its end");
    return b;
}

FileObserver recorder(SceneBundle& into) {
    return [&into](const std::string& path, const std::string& text) { into.files[path] = text; };
}

TextReader bundle_source(const SceneBundle& b) {
    return [&b](const std::string& path, std::string& reason) -> std::optional<std::string> {
        const auto it = b.files.find(path);
        if (it == b.files.end()) {
            reason = "not among the files rank 0 sent";
            return std::nullopt;
        }
        return it->second;
    };
}

}  // namespace luz::mpi
