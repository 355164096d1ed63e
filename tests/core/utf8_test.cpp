// Text written as JSON or HTML is valid UTF-8 whatever bytes came in (before: a non-UTF-8 EXR
// attribute made `info --json` fail with json type_error 316). Cases from RFC 3629 §3–4 and the
// Unicode Standard's "best practice" for U+FFFD substitution (one per invalid byte here).

#include "tirpol/core/utf8.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace tirpol {
namespace {

const std::string kFffd = "\xEF\xBF\xBD";

TEST(Utf8, ValidTextPassesUnchanged) {
    for (const std::string s :
         {"", "S0 W/(m²·sr)", "ε_S0 at 45°", "温度 K", "\xF0\x9F\x8C\xA1 thermometer"}) {
        EXPECT_TRUE(is_valid_utf8(s)) << s;
        EXPECT_EQ(valid_utf8(s), s);
    }
}

TEST(Utf8, EachInvalidByteBecomesOneReplacementCharacter) {
    EXPECT_EQ(valid_utf8("caf\xE9"), "caf" + kFffd);               // Latin-1 é
    EXPECT_EQ(valid_utf8("\xFF\xFE"), kFffd + kFffd);              // never valid in UTF-8
    EXPECT_EQ(valid_utf8("\xC0\xAF"), kFffd + kFffd);              // overlong '/' (RFC 3629 §10)
    EXPECT_EQ(valid_utf8("\xED\xA0\x80"), kFffd + kFffd + kFffd);  // UTF-16 surrogate D800
    EXPECT_EQ(valid_utf8("\xF4\x90\x80\x80"), kFffd + kFffd + kFffd + kFffd);  // above U+10FFFF
    EXPECT_EQ(valid_utf8("ab\xE2\x82"), "ab" + kFffd + kFffd);                 // truncated '€'
    EXPECT_TRUE(is_valid_utf8(valid_utf8("\x80\xBF\xC3")));
    EXPECT_FALSE(is_valid_utf8("caf\xE9"));
}

TEST(Utf8, JsonTextNeverThrowsOnInvalidBytesAndKeepsValidOnes) {
    nlohmann::json j;
    j["name"] = "pan\xE9l";
    j["caf\xE9"] = "ok °C";
    EXPECT_THROW((void)j.dump(), nlohmann::json::type_error);  // what tirpol used to do
    const std::string text = json_text(j);
    EXPECT_TRUE(is_valid_utf8(text));
    EXPECT_THAT(text, testing::HasSubstr("pan" + kFffd + "l"));
    EXPECT_THAT(text, testing::HasSubstr("ok °C"));
    EXPECT_NO_THROW((void)nlohmann::json::parse(text));
}

TEST(Utf8, AttributesJsonKeepsEveryType) {
    const Attributes a{
        {"n", 3}, {"x", 2.5}, {"s", std::string("\xFF")}, {"v", std::vector<double>{1, 2}}};
    const auto j = attributes_json(a);
    EXPECT_EQ(j["n"], 3);
    EXPECT_EQ(j["x"], 2.5);
    EXPECT_EQ(j["v"].size(), 2u);
    EXPECT_TRUE(is_valid_utf8(json_text(j)));
}

}  // namespace
}  // namespace tirpol
