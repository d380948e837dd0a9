// Tests of obj_text: a number token read in one pass (Tokens::next_plain_number, with its exact
// fast path for short decimals) gives what from_chars gives for the whole token; Lines ends a
// line at "\n", "\r\n" and a lone "\r", in time linear in the text.
#include "scene/obj_text.h"

#include <gtest/gtest.h>

#include <charconv>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace luz::obj_text {
namespace {

/// Checks next_plain_number on `token` (then a blank and "7", or the end of the line) against
/// from_chars on the token alone: the same acceptance and the same float, bit for bit.
void expect_as_from_chars(const std::string& token) {
    double d = 0;
    const char* end = token.data() + token.size();
    const auto [ptr, ec] = std::from_chars(token.data(), end, d);
    const bool accepted = !token.empty() && ec == std::errc() && ptr == end &&
                          std::fabs(d) <= std::numeric_limits<float>::max();
    for (const std::string& line : {token, token + " 7", "  " + token + "\t7"}) {
        Tokens tokens(line);
        float x = 0;
        ASSERT_EQ(tokens.next_plain_number(x), accepted) << "\"" << line << "\"";
        if (!accepted) continue;
        const float expected = static_cast<float>(d);
        EXPECT_EQ(std::memcmp(&x, &expected, sizeof x), 0) << "\"" << line << "\": " << x;
        std::string_view rest;
        EXPECT_EQ(tokens.next(rest), line != token) << "\"" << line << "\"";
        if (line != token) {
            EXPECT_EQ(rest, "7");
        }
    }
}

TEST(ObjText, PlainNumbersAsFromChars) {
    for (const char* t : {"0",
                          "-0",
                          "-0.0",
                          "0.5",
                          "1.",
                          ".5",
                          "-.5",
                          "-",
                          "+1",
                          "1e5",
                          "1.5e",
                          "1.5e-3",
                          "1E2",
                          "inf",
                          "-inf",
                          "nan",
                          "1.2.3",
                          "12abc",
                          "007",
                          "0.1",
                          "0.3",
                          "123456789012345",
                          "1234567890123456",
                          "999999999999999",
                          "0.000000000000001",
                          "9007199254740993",
                          "1e39",
                          "-3.4028235e38",
                          "1e-50",
                          "12345678.9012345"}) {
        expect_as_from_chars(t);
    }
}

TEST(ObjText, RandomDecimalsAsFromChars) {
    std::mt19937 rng(7);
    const auto below = [&](int n) { return static_cast<int>(rng() % static_cast<unsigned>(n)); };
    for (int i = 0; i < 200000; ++i) {
        std::string t = below(2) ? "-" : "";
        const int whole = below(18), fraction = below(4) ? below(18) : -1;
        for (int k = 0; k < whole; ++k) t += static_cast<char>('0' + below(10));
        if (fraction >= 0) t += '.';
        for (int k = 0; k < fraction; ++k) t += static_cast<char>('0' + below(10));
        if (below(20) == 0) t += "e" + std::to_string(below(80) - 40);
        if (!t.empty()) expect_as_from_chars(t);  // (an empty token: the next one is read)
    }
}

TEST(ObjText, LinesEndAtLfCrlfAndALoneCr) {
    Lines lines("a\nb\r\nc\rd\r\re\n\nf");
    std::vector<std::string> got;
    std::string_view line;
    while (lines.next(line)) got.emplace_back(line);
    EXPECT_EQ(got, (std::vector<std::string>{"a", "b", "c", "d", "", "e", "", "f"}));
    EXPECT_EQ(lines.number(), 8u);
}

// A text whose lines all end in a lone "\r" (classic Mac OS): each line is found without
// scanning the rest of the text for a "\n" again (that made a 3 MB OBJ file take 5 s).
TEST(ObjText, LinesEndingInALoneCrAreReadInLinearTime) {
    std::string text;
    for (int i = 0; i < 1000000; ++i) text += "v\r";
    const auto start = std::chrono::steady_clock::now();
    Lines lines(text);
    std::string_view line;
    size_t count = 0;
    while (lines.next(line)) count += line == "v";
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(count, 1000000u);
    EXPECT_LT(seconds, 5.0);  // milliseconds in a release build; minutes when quadratic
}

}  // namespace
}  // namespace luz::obj_text
