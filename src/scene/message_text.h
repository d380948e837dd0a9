// Text from the input as messages quote it: control characters and bytes that are not UTF-8
// escaped (a NUL would end the message; a stray byte would garble the terminal), long values
// shortened, so that every message stays one readable line.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace luz {

/// Longest quoted value shown whole, in characters; longer ones show their start.
inline constexpr std::size_t kMaxQuotedChars = 40;
/// Longest path or key path shown whole, in characters.
inline constexpr std::size_t kMaxPathChars = 200;

/// `s` with control characters as \uXXXX (\t kept) and bytes that are not UTF-8 as \xXX, cut
/// after `max_chars` characters (UTF-8) with "…" and " (N characters)" after it, e.g.
/// `aaaa… (10485760 characters)`.
std::string printable(std::string_view s, std::size_t max_chars = kMaxPathChars);

/// `s` in double quotes as printable() shows it, its own " and \ escaped by a backslash (so the
/// quotes end where the value does), e.g. `"aaaa…" (10485760 characters)`.
std::string quote(std::string_view s, std::size_t max_chars = kMaxQuotedChars);

/// "12.5 GiB", "3.0 MiB", or "512 bytes".
std::string bytes_text(uint64_t bytes);

}  // namespace luz
