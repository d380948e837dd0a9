// The bytes luz-mpi's processes send each other: little helpers to append and read back
// integers and strings; reading past the end throws WireError.
#pragma once

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <string_view>

namespace luz::mpi {

struct WireError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

inline void put_u64(std::string& out, uint64_t v) {
    out.append(reinterpret_cast<const char*>(&v), sizeof v);
}
inline void put_bytes(std::string& out, std::string_view bytes) {
    put_u64(out, bytes.size());
    out.append(bytes);
}

/// Reads what put_u64 and put_bytes wrote, in order.
class WireReader {
  public:
    explicit WireReader(std::string_view in) : in_(in) {}
    uint64_t u64() {
        uint64_t v;
        need(sizeof v);
        std::memcpy(&v, in_.data(), sizeof v);
        in_.remove_prefix(sizeof v);
        return v;
    }
    std::string_view bytes() {
        const uint64_t n = u64();
        need(n);
        const std::string_view b = in_.substr(0, n);
        in_.remove_prefix(n);
        return b;
    }
    bool done() const { return in_.empty(); }

  private:
    void need(uint64_t n) const {
        if (in_.size() < n) throw WireError("the message is truncated");
    }
    std::string_view in_;
};

}  // namespace luz::mpi
