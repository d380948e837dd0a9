// The reading shared by the OBJ and MTL checking passes: lines numbered as tinyobjloader counts
// them, blank-separated tokens, strict numbers, and errors at FILE:LINE.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace luz::obj_text {

/// "FILE:LINE: ".
std::string at(const std::string& file, size_t line);

/// Throws InputError "FILE:LINE: what".
[[noreturn]] void fail_at(const std::string& file, size_t line, const std::string& what);

/// Text without a leading UTF-8 byte order mark.
std::string_view without_bom(std::string_view text);

inline bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

/// The lines of a text, numbered from 1; "\n", "\r\n" and a lone "\r" end a line (as
/// tinyobjloader counts them).
class Lines {
  public:
    explicit Lines(std::string_view text) : text_(text) {}

    bool next(std::string_view& line) {
        if (pos_ >= text_.size()) return false;
        // the next '\n' (found once, kept while lines ending in a lone '\r' come before it),
        // then any '\r' before it: memchr() scans, each character looked at once
        if (newline_ == std::string_view::npos || newline_ < pos_) {
            newline_ = text_.find('\n', pos_);
            if (newline_ == std::string_view::npos) newline_ = text_.size();
        }
        size_t end = newline_;
        if (const size_t cr = text_.substr(0, end).find('\r', pos_); cr != std::string_view::npos)
            end = cr;
        line = text_.substr(pos_, end - pos_);
        pos_ = end;
        if (end < text_.size()) {
            pos_ = end + 1;
            if (text_[end] == '\r' && pos_ < text_.size() && text_[pos_] == '\n') ++pos_;
        }
        ++number_;
        return true;
    }
    size_t number() const { return number_; }

  private:
    std::string_view text_;
    size_t pos_ = 0;
    size_t newline_ = std::string_view::npos;  // the next '\n' once found (text_.size(): none)
    size_t number_ = 0;
};

/// The whitespace-separated tokens of a line.
class Tokens {
  public:
    explicit Tokens(std::string_view line) : rest_(line) {}
    bool next(std::string_view& token) {
        size_t i = 0;
        while (i < rest_.size() && is_blank(rest_[i])) ++i;
        size_t j = i;
        while (j < rest_.size() && !is_blank(rest_[j])) ++j;
        token = rest_.substr(i, j - i);
        rest_.remove_prefix(j);
        return !token.empty();
    }
    /// The next token when it is a plain number (no '+' sign) that read_number() accepts, as
    /// that float; otherwise false, and nothing is read (read_number() then gives the error).
    /// One pass over its characters: the number ends at a blank or at the end of the line.
    bool next_plain_number(float& x);
    /// What is left after the tokens read so far, without leading blanks.
    std::string_view rest() const {
        size_t i = 0;
        while (i < rest_.size() && is_blank(rest_[i])) ++i;
        return rest_.substr(i);
    }

  private:
    std::string_view rest_;
};

/// A number token as a float: the whole token must be a number, finite, in float range.
float read_number(std::string_view token, const std::string& file, size_t line,
                  std::string_view statement);

/// Reads the numbers of a statement (at least `min_count`, at most `max_count`) into `out`;
/// returns how many.
int read_numbers(Tokens& tokens, float* out, int min_count, int max_count, const std::string& file,
                 size_t line, std::string_view statement);

}  // namespace luz::obj_text
