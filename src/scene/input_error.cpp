// InputError's message: a NUL quoted from the input kept as "\u0000" (luz/errors.h).
#include "luz/errors.h"

namespace luz {

std::string InputError::without_nul(const std::string& s) {
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

}  // namespace luz
