// The words of a render's progress line: the share done and the time left, as `luz render`'s
// bar and Python's progress bar show them.
#pragma once

#include <string>

namespace luz {

/// The words after the bar: the share done (format_percent()) and the time left, e.g.
/// " 42%  ETA 3s", "0.04%  ETA 2h05m"; "ETA --" only while nothing is done, "done in 1.2s" at 1.
/// Python's bar (luz._progress) shows the same words.
std::string format_status(double fraction, double elapsed_s);

/// The share done, rounded down: "0.04%" below 1 %, "4.2%" below 10 %, " 42%" above, so that
/// a render whose pixels take seconds moves from its first pixels on.
std::string format_percent(double fraction);

/// A duration in seconds as a short human string: "3s", "2m05s", "1h02m".
std::string format_duration(double seconds);

}  // namespace luz
