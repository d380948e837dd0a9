// Tests of the scene's JSON text (scene/json_text.h, json_builder.h): duplicate keys and NUL
// characters refused at line:column, the memory limit while parsing, linear time for objects of
// many keys, and messages that stay short whatever the input quotes.
#include "scene/json_text.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>

#include "sanitizer.h"
#include "scene/input_error.h"
#include "scene/message_text.h"
#include "scene/scene_loader.h"
#include "scene/text_files.h"

namespace luz {
namespace {

using loader::parse_text;
using ::testing::HasSubstr;

/// The InputError message parse_text() throws for `text`, or "(no error)".
std::string json_error_of(const std::string& text) {
    try {
        parse_text(text, "s.json");
    } catch (const InputError& e) {
        return e.what();
    }
    return "(no error)";
}

TEST(JsonText, ADuplicateKeyNamesBothPlaces) {
    EXPECT_EQ(json_error_of("{\"a\": 1,\n  \"b\": {\"a\": 2},\n  \"a\": 3}"),
              "s.json:3:3: duplicate key \"a\" (first at 1:2): a key may appear once in an object");
    // an escaped spelling is the same key; an escaped quote inside a key is skipped over
    EXPECT_THAT(json_error_of(R"({"a\"b": 1, "a\u0022b": 2})"),
                HasSubstr("s.json:1:13: duplicate key \"a\\\"b\" (first at 1:2)"));
    // the same key in different objects is fine
    EXPECT_EQ(json_error_of(R"({"x": {"a": 1}, "y": {"a": 1}, "z": [{"a": 1}, {"a": 2}]})"),
              "(no error)");
}

TEST(JsonText, ADuplicateAmongManyKeysIsFoundByTheIndex) {
    std::string text = "{";
    for (int i = 0; i < 100; ++i)
        text += "\"k" + std::to_string(i) + "\": " + std::to_string(i) + ",";
    text += "\n\"k42\": 0}";
    EXPECT_THAT(json_error_of(text), HasSubstr("s.json:2:1: duplicate key \"k42\" (first at 1:"));
}

TEST(JsonText, NulCharactersInKeysAndStringsAreRefusedWithTheirReason) {
    EXPECT_EQ(json_error_of(R"({"objects\u0000": []})"),
              "s.json:1:2: key \"objects\\u0000\": a NUL character (\\u0000) is not allowed");
    EXPECT_EQ(json_error_of(R"({"file": "a.obj\u0000x"})"),
              "s.json:1:10: string \"a.obj\\u0000x\": a NUL character (\\u0000) is not allowed");
}

TEST(JsonText, AnObjectOfTwoHundredThousandKeysParsesInLinearTime) {
    LUZ_SPEED_TEST();
    // ordered_json's own parser searches the keys before each insertion: minutes for this
    std::string text = "{\"materials\": {";
    for (int i = 0; i < 200000; ++i) {
        text += (i ? ", \"m" : "\"m") + std::to_string(i) + "\": {\"kd\": 0.5}";
    }
    text += "}}";
    const auto start = std::chrono::steady_clock::now();
    const loader::Json doc = parse_text(text, "s.json");
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ASSERT_EQ(doc["materials"].size(), 200000u);
    EXPECT_EQ(doc["materials"].begin().key(), "m0");  // the file's order is kept
    EXPECT_LT(seconds, 3.0);
}

TEST(JsonText, ADocumentLargerThanTheMemoryLimitIsRefusedWhileParsing) {
    std::string text = "{\"objects\": [";
    for (int i = 0; i < 20000; ++i) text += (i ? ", " : "") + std::string(R"({"type": "sphere"})");
    text += "]}";
    set_memory_limit(1 << 20);
    const std::string e = json_error_of(text);
    set_memory_limit(UINT64_MAX);
    EXPECT_THAT(e, HasSubstr("the scene needs more memory than the 1.0 MiB limit"));
    EXPECT_THAT(e, HasSubstr("--max-memory"));
    EXPECT_EQ(json_error_of(text), "(no error)");
}

TEST(JsonText, LongValuesAndTokensAreShortenedInMessages) {
    const std::string huge(10485760, 'a');
    std::string message;
    try {
        parse_scene(R"({"objects": [{"type": ")" + huge + "\"}]}", "s.json", "");
    } catch (const InputError& e) {
        message = e.what();
    }
    EXPECT_THAT(message, HasSubstr("objects.0.type: unknown value \"" + std::string(40, 'a') +
                                   "\xE2\x80\xA6\" (10485760 characters)"));
    EXPECT_LT(message.size(), 300u);
    // a syntax error's "last read" token: an unterminated string
    const std::string e = json_error_of("{\"a\": \"" + huge);
    EXPECT_THAT(e, HasSubstr("JSON syntax error"));
    EXPECT_LT(e.size(), 300u);
    // a key that is not known
    try {
        parse_scene(R"({"objects": [{"type": "sphere", ")" + huge + "\": 1}]}", "s.json", "");
    } catch (const InputError& e) {
        message = e.what();
    }
    EXPECT_THAT(message, HasSubstr("(10485770 characters): unknown key"));
    EXPECT_LT(message.size(), 400u);
}

TEST(JsonText, OverridesAreCheckedTheSameWay) {
    EXPECT_THROW(parse_set(R"(materials={"a": {}, "a": {}})"), InputError);
    try {
        parse_set(R"(materials={"a": {}, "a": {}})");
    } catch (const InputError& e) {
        EXPECT_THAT(e.what(), HasSubstr("duplicate key \"a\""));
    }
    try {
        parse_scene(R"({"objects": [{"type": "sphere"}]})", "s.json", "",
                    {Override{std::string("objects\0x", 9), "1"}});
        ADD_FAILURE() << "a NUL in a key path was accepted";
    } catch (const InputError& e) {
        EXPECT_THAT(e.what(),
                    HasSubstr("a NUL character (\\u0000) in key path \"objects\\u0000x\""));
    }
}

TEST(MessageText, QuotesEscapeAndShorten) {
    EXPECT_EQ(quote("abc"), "\"abc\"");
    EXPECT_EQ(quote(std::string("a\0b\n", 4)), "\"a\\u0000b\\u000A\"");
    EXPECT_EQ(quote(std::string(50, 'x'), 4), "\"xxxx\xE2\x80\xA6\" (50 characters)");
    // characters, not bytes: é is two bytes, one character, never cut in half
    EXPECT_EQ(printable("\xC3\xA9\xC3\xA9\xC3\xA9", 2),
              "\xC3\xA9\xC3\xA9\xE2\x80\xA6 (3 characters)");
    // a quoted value's own quotes and backslashes escaped, so that the quotes end where it does
    EXPECT_EQ(quote("ab\"c\\d"), "\"ab\\\"c\\\\d\"");
    EXPECT_EQ(printable("a\\b"), "a\\b");  // a path keeps its backslashes
    // bytes that are not UTF-8 (a stray byte, a cut or overlong sequence, a surrogate) as \xXX
    EXPECT_EQ(printable("a\xFF"
                        "b"),
              "a\\xFFb");
    EXPECT_EQ(quote("\xC3"), "\"\\xC3\"");
    EXPECT_EQ(printable("\xC0\xAF"), "\\xC0\\xAF");
    EXPECT_EQ(printable("\xED\xA0\x80"), "\\xED\\xA0\\x80");
    EXPECT_EQ(printable("\xF0\x9F\x99\x82 \xE2\x82\xAC"), "\xF0\x9F\x99\x82 \xE2\x82\xAC");
    EXPECT_EQ(printable(std::string(3, '\xFF'), 2), "\\xFF\\xFF\xE2\x80\xA6 (3 characters)");
    EXPECT_EQ(bytes_text(3u << 20), "3.0 MiB");
}

}  // namespace
}  // namespace luz
