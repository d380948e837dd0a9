// ProgressBar (src/app/progress_bar.h): the line it draws, when it draws, and its thread safety.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include "app/progress_bar.h"

namespace luz {
namespace {

/// Everything written to a temporary FILE*.
std::string contents(std::FILE* f) {
    std::fflush(f);
    std::rewind(f);
    std::string s;
    char buf[4096];
    size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) s.append(buf, n);
    return s;
}

TEST(FormatProgress, BarPercentAndEta) {
    EXPECT_EQ(format_progress(0.42, 2.1, 10), "[####------]  42%  ETA 3s");
    EXPECT_EQ(format_progress(0.0, 0.0, 4), "[----] 0.00%  ETA --");
    EXPECT_EQ(format_progress(1.0, 5.04, 4), "[####] 100%  done in 5.0s");
    EXPECT_EQ(format_progress(1.0, 125, 4), "[####] 100%  done in 2m05s");
}

TEST(FormatProgress, BelowTenPercentWithADecimal) {
    EXPECT_EQ(format_percent(0.004), "0.40%");
    EXPECT_EQ(format_percent(0.0004), "0.04%");
    EXPECT_EQ(format_percent(0.042), "4.2%");
    EXPECT_EQ(format_percent(0.0999), "9.9%");  // rounded down: never 10.0 % before it is
    EXPECT_EQ(format_percent(0.1), " 10%");
    EXPECT_EQ(format_percent(0.9999), " 99%");
    EXPECT_EQ(format_percent(0.00001), "0.00%");
    EXPECT_EQ(format_progress(0.004, 1.0, 4), "[----] 0.40%  ETA 4m09s");
}

TEST(FormatProgress, TimeLeftAsSoonAsOnePixelIsDone) {
    // One pixel of 320×240 done after 0.3 s: the rest at that rate, not "ETA --".
    EXPECT_EQ(format_status(1.0 / 76800, 0.3), "0.00%  ETA 6h24m");
    EXPECT_EQ(format_status(0.5, 0.1), " 50%  ETA 1s");
    EXPECT_EQ(format_status(0.5, 10.0), " 50%  ETA 10s");
    EXPECT_EQ(format_status(0.0, 5.0), "0.00%  ETA --");  // nothing done: nothing to go by
}

TEST(FormatProgress, ClampsOutOfRangeFractions) {
    EXPECT_EQ(format_progress(-1.0, 1.0, 4), "[----] 0.00%  ETA --");
    EXPECT_EQ(format_progress(7.0, 1.0, 4), "[####] 100%  done in 1.0s");
}

TEST(FormatDuration, SecondsMinutesHours) {
    EXPECT_EQ(format_duration(0.2), "1s");
    EXPECT_EQ(format_duration(59), "59s");
    EXPECT_EQ(format_duration(125), "2m05s");
    EXPECT_EQ(format_duration(3720), "1h02m");
}

TEST(ProgressBar, DisabledWritesNothing) {
    std::FILE* f = std::tmpfile();
    {
        ProgressBar bar(false, f);
        bar.update(0.5);
        bar.finish();
    }
    EXPECT_EQ(contents(f), "");
    std::fclose(f);
}

TEST(ProgressBar, DrawsThenFinishesWithANewline) {
    std::FILE* f = std::tmpfile();
    ProgressBar bar(true, f, 0.0);
    bar.update(0.5);
    std::string s = contents(f);
    EXPECT_NE(s.find(" 50%"), std::string::npos) << s;
    std::fseek(f, 0, SEEK_END);
    bar.finish();
    s = contents(f);
    EXPECT_NE(s.find("100%"), std::string::npos) << s;
    EXPECT_EQ(s.back(), '\n');
    bar.update(0.7);  // after finish: nothing more
    EXPECT_EQ(contents(f), s);
    std::fclose(f);
}

TEST(ProgressBar, RedrawsAtMostOncePerInterval) {
    std::FILE* f = std::tmpfile();
    ProgressBar bar(true, f, 3600.0);
    for (int i = 1; i <= 100; ++i) bar.update(i / 100.0);
    const std::string s = contents(f);
    EXPECT_EQ(std::count(s.begin(), s.end(), '\r'), 1) << s;
    std::fseek(f, 0, SEEK_END);
    bar.finish();  // the final state is always drawn
    EXPECT_NE(contents(f).find("100%"), std::string::npos);
    std::fclose(f);
}

TEST(ProgressBar, AbandonEndsTheLineWithoutCompleting) {
    std::FILE* f = std::tmpfile();
    {
        ProgressBar bar(true, f, 0.0);
        bar.update(0.3);
        bar.abandon();
    }
    const std::string s = contents(f);
    EXPECT_EQ(s.find("100%"), std::string::npos) << s;
    EXPECT_EQ(s.back(), '\n');
    EXPECT_EQ(std::count(s.begin(), s.end(), '\n'), 1);
    std::fclose(f);
}

TEST(ProgressBar, ManyThreadsAtOnce) {
    std::FILE* f = std::tmpfile();
    ProgressBar bar(true, f, 0.0);
    std::vector<std::thread> threads;
    for (int t = 0; t < 8; ++t) {
        threads.emplace_back([&bar, t] {
            for (int i = 0; i < 2000; ++i) bar.update((t * 2000 + i) / 16000.0);
        });
    }
    for (auto& th : threads) th.join();
    bar.finish();
    const std::string s = contents(f);
    EXPECT_NE(s.find("100%"), std::string::npos);
    EXPECT_EQ(std::count(s.begin(), s.end(), '\n'), 1);
    std::fclose(f);
}

}  // namespace
}  // namespace luz
