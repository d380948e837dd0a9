// ProgressBar: the render's progress on standard error, "[#####-----]  42%  ETA 3s" (docs/CLI.md),
// drawn only on a terminal; safe to update from any worker thread.
#pragma once

#include <chrono>
#include <cstdio>
#include <mutex>
#include <string>

#include "luz/progress_text.h"

namespace luz {

/// One line of the bar for `fraction` done (0..1) after `elapsed_s` seconds, e.g.
/// "[#####-----]  42%  ETA 3s": the bar of `bar_width` cells, then format_status().
std::string format_progress(double fraction, double elapsed_s, int bar_width = 30);

/// True when standard error is a terminal (where a progress bar makes sense).
bool stderr_is_terminal();

class ProgressBar {
  public:
    /// Draws to `out` only when `enabled`; at most one redraw per `min_interval_s` seconds.
    explicit ProgressBar(bool enabled, std::FILE* out = stderr, double min_interval_s = 0.1);
    ~ProgressBar();
    ProgressBar(const ProgressBar&) = delete;
    ProgressBar& operator=(const ProgressBar&) = delete;

    /// Reports `fraction` done (0..1). Thread-safe and cheap: a call that finds another
    /// thread drawing, or comes too soon after the last redraw, returns at once.
    void update(double fraction);

    /// Draws the finished bar and ends its line.
    void finish();

    /// Ends the bar's line without drawing it complete (after a failure), so that a
    /// following message starts on a new line.
    void abandon();

    /// Prints `line` on standard error on a line of its own (even when the bar is disabled),
    /// the bar redrawn after it; any thread.
    void interject(const std::string& line);

    bool enabled() const { return enabled_; }

  private:
    void draw_locked(double fraction);

    using Clock = std::chrono::steady_clock;
    bool enabled_;
    std::FILE* out_;
    double min_interval_s_;
    std::mutex mutex_;
    Clock::time_point start_;
    Clock::time_point last_draw_;
    double best_fraction_ = 0.0;
    bool drawn_ = false;
    bool done_ = false;
};

}  // namespace luz
