// ProgressBar: drawing and rate limiting of the render's progress line on standard error.
#include "app/progress_bar.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>

namespace luz {

std::string format_progress(double fraction, double elapsed_s, int bar_width) {
    if (!(fraction >= 0)) fraction = 0;  // also catches NaN
    fraction = std::min(fraction, 1.0);
    bar_width = std::max(bar_width, 1);
    const int filled = static_cast<int>(std::floor(fraction * bar_width));
    std::string line = "[";
    line.append(static_cast<size_t>(filled), '#');
    line.append(static_cast<size_t>(bar_width - filled), '-');
    return line + "] " + format_status(fraction, elapsed_s);
}

bool stderr_is_terminal() { return isatty(STDERR_FILENO) == 1; }

ProgressBar::ProgressBar(bool enabled, std::FILE* out, double min_interval_s)
    : enabled_(enabled && out != nullptr),
      out_(out),
      min_interval_s_(min_interval_s),
      start_(Clock::now()),
      last_draw_(start_) {}

ProgressBar::~ProgressBar() { abandon(); }

void ProgressBar::update(double fraction) {
    if (!enabled_) return;
    std::unique_lock lock(mutex_, std::try_to_lock);
    if (!lock.owns_lock() || done_) return;  // another thread is drawing: skip this report
    best_fraction_ = std::max(best_fraction_, fraction);  // reports may arrive out of order
    const auto now = Clock::now();
    if (drawn_ && std::chrono::duration<double>(now - last_draw_).count() < min_interval_s_) {
        return;
    }
    last_draw_ = now;
    draw_locked(best_fraction_);
}

void ProgressBar::draw_locked(double fraction) {
    const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
    const std::string line = format_progress(fraction, elapsed);
    // \r returns to the start of the line, \033[K clears what a longer line left behind
    std::fprintf(out_, "\r%s\033[K", line.c_str());
    std::fflush(out_);
    drawn_ = true;
}

void ProgressBar::finish() {
    if (!enabled_) return;
    std::lock_guard lock(mutex_);
    if (done_) return;
    draw_locked(1.0);
    std::fputc('\n', out_);
    std::fflush(out_);
    done_ = true;
}

void ProgressBar::abandon() {
    if (!enabled_) return;
    std::lock_guard lock(mutex_);
    if (done_) return;
    if (drawn_) {
        std::fputc('\n', out_);
        std::fflush(out_);
    }
    done_ = true;
}

void ProgressBar::interject(const std::string& line) {
    std::lock_guard lock(mutex_);
    if (enabled_ && drawn_ && !done_) {
        std::fprintf(out_, "\r\033[K%s\n", line.c_str());
        draw_locked(best_fraction_);
    } else {
        std::fprintf(out_ ? out_ : stderr, "%s\n", line.c_str());
        std::fflush(out_ ? out_ : stderr);
    }
}

}  // namespace luz
