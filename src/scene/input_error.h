// InputError: bad input (exit 2). Its message names the file, the place and what is wrong.
#pragma once

#include <stdexcept>
#include <string>

namespace luz {

struct InputError : std::runtime_error {
    /// A NUL quoted from the input is kept as "\u0000": what() is a C string, and would end
    /// the message there, before the reason.
    explicit InputError(const std::string& message) : std::runtime_error(without_nul(message)) {}
    explicit InputError(const char* message) : std::runtime_error(message) {}

  private:
    static std::string without_nul(const std::string& s) {
        if (s.find('\0') == std::string::npos) return s;
        std::string out;
        for (const char c : s) {
            if (c == '\0') {
                out += "\\u0000";
            } else {
                out += c;
            }
        }
        return out;
    }
};

}  // namespace luz
