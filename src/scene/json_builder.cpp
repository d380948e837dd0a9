// The SAX handler that builds a scene document (see json_builder.h).
#include "scene/json_builder.h"

#include <iterator>
#include <memory>
#include <unordered_map>
#include <utility>
#include <vector>

#include "scene/message_text.h"

namespace luz::loader {
namespace {

/// A byte iterator over the text that publishes how far the parser has read: nlohmann's SAX
/// events carry no position, and the parser reads one byte at a time through it.
class TrackingIterator {
  public:
    using iterator_category = std::forward_iterator_tag;
    using value_type = char;
    using difference_type = std::ptrdiff_t;
    using pointer = const char*;
    using reference = const char&;

    TrackingIterator(const char* p, const char** read_to) : p_(p), read_to_(read_to) {}
    reference operator*() const { return *p_; }
    TrackingIterator& operator++() {
        *read_to_ = ++p_;
        return *this;
    }
    TrackingIterator operator++(int) {
        TrackingIterator old = *this;
        ++*this;
        return old;
    }
    bool operator==(const TrackingIterator& o) const { return p_ == o.p_; }

  private:
    const char* p_;
    const char** read_to_;
};

using Members = Json::object_t::Container;

/// Estimated heap bytes of a std::string of `n` characters beyond its own 32 (SSO up to 15).
uint64_t string_heap(std::size_t n) { return n > 15 ? n + 1 + 16 : 0; }

// Estimated bytes per part of the document, as the resident size of parsed scenes measured
// them (nlohmann's layout, vectors' growth, the allocator's overhead).
constexpr uint64_t kMemberBytes = 128;    // one object member: key and value
constexpr uint64_t kElementBytes = 48;    // one array element
constexpr uint64_t kContainerBytes = 64;  // an object's or array's own allocation
constexpr uint64_t kStringBytes = 80;     // a string value's own allocation
/// Above this many members an open object indexes its keys (below, a linear search is faster).
constexpr std::size_t kIndexFrom = 16;

class Builder : public nlohmann::json_sax<Json> {
  public:
    Builder(std::string_view text, const char* const* read_to, uint64_t budget, Json& root)
        : text_(text), read_to_(read_to), budget_(budget), root_(root) {}

    std::optional<JsonProblem> problem;

    bool null() override { return place(Json(nullptr), 0) != nullptr; }
    bool boolean(bool b) override { return place(Json(b), 0) != nullptr; }
    bool number_integer(number_integer_t v) override { return place(Json(v), 0) != nullptr; }
    bool number_unsigned(number_unsigned_t v) override { return place(Json(v), 0) != nullptr; }
    bool number_float(number_float_t v, const string_t&) override {
        return place(Json(v), 0) != nullptr;
    }
    bool string(string_t& s) override {
        if (s.find('\0') != string_t::npos) {
            return stop(JsonProblem::Kind::nul, string_start(),
                        "string " + quote(s) + ": a NUL character (\\u0000) is not allowed");
        }
        const uint64_t cost = kStringBytes + string_heap(s.size());
        return place(Json(std::move(s)), cost) != nullptr;
    }
    bool binary(binary_t&) override { return true; }  // not in JSON text

    bool start_object(std::size_t) override { return open(Json::object()); }
    bool start_array(std::size_t) override { return open(Json::array()); }
    bool end_object() override { return close(); }
    bool end_array() override { return close(); }

    bool key(string_t& k) override {
        const std::size_t start = string_start();
        if (k.find('\0') != string_t::npos) {
            return stop(JsonProblem::Kind::nul, start,
                        "key " + quote(k) + ": a NUL character (\\u0000) is not allowed");
        }
        Frame& f = frames_[depth_ - 1];
        Members& members = f.value->get_ref<Json::object_t&>();
        // A key already in this object?
        std::size_t seen = members.size();
        if (f.index) {
            const auto [it, fresh] = f.index->emplace(k, members.size());
            if (!fresh) seen = it->second;
        } else {
            for (std::size_t i = 0; i < members.size(); ++i) {
                if (members[i].first == k) seen = i;
            }
            if (members.size() + 1 >= kIndexFrom) {
                f.index = std::make_unique<std::unordered_map<std::string, std::size_t>>();
                for (std::size_t i = 0; i < members.size(); ++i) {
                    f.index->emplace(members[i].first, i);
                }
                f.index->emplace(k, members.size());
            }
        }
        if (seen < members.size()) {
            JsonProblem p{JsonProblem::Kind::duplicate,
                          start,
                          f.key_offsets[seen],
                          "duplicate key " + quote(k),
                          {}};
            problem = std::move(p);
            return false;
        }
        if (!spend(kMemberBytes + string_heap(k.size()))) return false;
        f.key_offsets.push_back(start);
        members.emplace_back(std::move(k), nullptr);
        slot_ = &members.back().second;
        return true;
    }

    bool parse_error(std::size_t position, const std::string& last_token,
                     const nlohmann::detail::exception& ex) override {
        JsonProblem p;
        p.what = ex.what();
        p.token = last_token;
        // The position counts the bytes read: the offending one is at position − 1; a number
        // out of range is pointed at from its start.
        p.offset = position > 0 ? position - 1 : 0;
        if (ex.id == 406) {
            p.kind = JsonProblem::Kind::range;
            p.offset = position >= last_token.size() ? position - last_token.size() : 0;
        }
        problem = std::move(p);
        return false;
    }

  private:
    struct Frame {
        Json* value = nullptr;
        std::vector<std::size_t> key_offsets;  ///< an object's keys' offsets, in member order
        std::unique_ptr<std::unordered_map<std::string, std::size_t>> index;  ///< key → member
    };

    std::size_t read_offset() const { return static_cast<std::size_t>(*read_to_ - text_.data()); }

    /// The offset of the opening quote of the string the parser has just read.
    std::size_t string_start() const {
        std::size_t i = read_offset();
        if (i >= 2) i -= 2;  // before the closing quote
        // back to the first quote not escaped (preceded by an even number of backslashes)
        while (i > 0) {
            if (text_[i] == '"') {
                std::size_t backslashes = 0;
                while (backslashes < i && text_[i - 1 - backslashes] == '\\') ++backslashes;
                if (backslashes % 2 == 0) break;
            }
            --i;
        }
        return i;
    }

    bool stop(JsonProblem::Kind kind, std::size_t offset, std::string what) {
        problem = JsonProblem{kind, offset, 0, std::move(what), {}};
        return false;
    }

    bool spend(uint64_t bytes) {
        used_ += bytes;
        if (used_ <= budget_) return true;
        return stop(JsonProblem::Kind::memory, read_offset(), "");
    }

    /// Puts `v` where the next value goes (the root, an array's end, the member of the last
    /// key); returns it, or nullptr when the budget is passed.
    Json* place(Json&& v, uint64_t cost) {
        if (depth_ == 0) {
            root_ = std::move(v);
            return &root_;
        }
        Json& parent = *frames_[depth_ - 1].value;
        if (parent.is_array()) {
            if (!spend(cost + kElementBytes)) return nullptr;
            auto& elements = parent.get_ref<Json::array_t&>();
            elements.push_back(std::move(v));
            return &elements.back();
        }
        if (!spend(cost)) return nullptr;
        *slot_ = std::move(v);
        return slot_;
    }

    bool open(Json&& container) {
        Json* j = place(std::move(container), kContainerBytes);
        if (!j) return false;
        // frames are kept once made, so that their vectors are reused
        if (depth_ == frames_.size()) frames_.emplace_back();
        Frame& f = frames_[depth_++];
        f.value = j;
        f.key_offsets.clear();
        f.index.reset();
        return true;
    }

    bool close() {
        --depth_;
        return true;
    }

    std::string_view text_;
    const char* const* read_to_;
    uint64_t budget_, used_ = 0;
    Json& root_;
    std::vector<Frame> frames_;
    std::size_t depth_ = 0;
    Json* slot_ = nullptr;  ///< the member the last key made
};

}  // namespace

std::optional<JsonProblem> build_json(std::string_view text, Json& out, uint64_t memory_budget) {
    const char* read_to = text.data();
    Builder builder(text, &read_to, memory_budget, out);
    const TrackingIterator first(text.data(), &read_to), last(text.data() + text.size(), &read_to);
    if (Json::sax_parse(first, last, &builder)) return std::nullopt;
    if (!builder.problem) builder.problem = JsonProblem{};  // not expected: stopped, no reason
    return builder.problem;
}

}  // namespace luz::loader
