// The words of a render's progress ("4.2%  ETA 1m05s"), shared by the CLI's bar and Python's.
#include "luz/progress_text.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace luz {

std::string format_duration(double seconds) {
    if (!std::isfinite(seconds) || seconds < 0) return "--";
    const long long s = static_cast<long long>(std::ceil(seconds));
    char buf[48];
    if (s < 60) {
        std::snprintf(buf, sizeof buf, "%llds", s);
    } else if (s < 3600) {
        std::snprintf(buf, sizeof buf, "%lldm%02llds", s / 60, s % 60);
    } else {
        std::snprintf(buf, sizeof buf, "%lldh%02lldm", s / 3600, (s % 3600) / 60);
    }
    return buf;
}

std::string format_percent(double fraction) {
    if (!(fraction >= 0)) fraction = 0;  // also catches NaN
    fraction = std::min(fraction, 1.0);
    // Rounded down at the precision shown, so that 100 % means done and 0.00 % nothing done.
    char buf[32];
    const double percent = fraction * 100.0;
    if (percent < 1.0) {
        std::snprintf(buf, sizeof buf, "%.2f%%", std::floor(percent * 100.0) / 100.0);
    } else if (percent < 10.0) {
        std::snprintf(buf, sizeof buf, "%.1f%%", std::floor(percent * 10.0) / 10.0);
    } else {
        std::snprintf(buf, sizeof buf, "%3d%%", static_cast<int>(std::floor(percent)));
    }
    return buf;
}

std::string format_status(double fraction, double elapsed_s) {
    if (!(fraction >= 0)) fraction = 0;
    fraction = std::min(fraction, 1.0);
    std::string line = format_percent(fraction) + "  ";
    if (fraction >= 1.0) {
        if (elapsed_s < 60) {
            char buf[32];
            std::snprintf(buf, sizeof buf, "done in %.1fs", elapsed_s);
            line += buf;
        } else {
            line += "done in " + format_duration(elapsed_s);
        }
    } else if (fraction > 0) {
        // time left, assuming the rest goes at the average rate so far: known as soon as a
        // pixel is done
        line += "ETA " + format_duration(elapsed_s * (1.0 - fraction) / fraction);
    } else {
        line += "ETA --";  // nothing done yet
    }
    return line;
}

}  // namespace luz
