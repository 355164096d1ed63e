// The one parser of numbers in option values and the option limits table
// (core/src/option_values.cpp): what the CLI's numeric options and the numbers inside text values
// (`--bound sigma=0.05:0.8`) accept.

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "tirpol/core/limits.h"

namespace tirpol {
namespace {

TEST(ParseNumber, AcceptsOnlyTextThatIsAllOneNumber) {
    EXPECT_EQ(parse_number("0.25"), 0.25);
    EXPECT_EQ(parse_number("-3e2"), -300.0);
    EXPECT_FALSE(parse_number(""));
    EXPECT_FALSE(parse_number("0.25x"));
    EXPECT_FALSE(parse_number("sigma"));
    EXPECT_FALSE(parse_number(" "));
}

TEST(ParseNumber, OverflowAndInfinityAreInfiniteAndNanIsNan) {
    // strtod's syntax, as CLI11 converts option values: the value is read, then refused as not
    // finite by option_number_problem.
    ASSERT_TRUE(parse_number("1e400"));
    EXPECT_TRUE(std::isinf(*parse_number("1e400")));
    EXPECT_TRUE(std::isinf(*parse_number("-inf")));
    EXPECT_TRUE(std::isnan(*parse_number("nan")));
}

TEST(OptionNumberProblem, RefusesNonFiniteValuesNamingThem) {
    EXPECT_EQ(option_number_problem("nan", nullptr), "expected a finite number, got 'nan'");
    EXPECT_EQ(option_number_problem("1e400", nullptr), "expected a finite number, got '1e400'");
    EXPECT_EQ(option_number_problem("42", nullptr), "");
    // Not a number at all: left to the option parser, which names the expected type.
    EXPECT_EQ(option_number_problem("abc", nullptr), "");
}

TEST(OptionNumberProblem, HoldsTableOptionsToTheirLimitsInclusive) {
    const OptionLimit* band = option_limit("planck", "--band-um");
    ASSERT_NE(band, nullptr);
    EXPECT_EQ(band->lo, limits::kMinWavelengthUm);
    EXPECT_EQ(band->hi, limits::kMaxWavelengthUm);
    EXPECT_EQ(option_number_problem("0.1", band), "");
    EXPECT_EQ(option_number_problem("1000", band), "");
    const std::string beyond = option_number_problem("1e7", band);
    EXPECT_NE(beyond.find("1e7 is outside [0.1, 1000]"), std::string::npos) << beyond;
    EXPECT_NE(beyond.find("wavelength"), std::string::npos) << beyond;
}

TEST(OptionLimit, SubcommandEntriesApplyOnlyThereAndWildcardsEverywhere) {
    EXPECT_NE(option_limit("fit", "--starts"), nullptr);
    EXPECT_EQ(option_limit("render", "--starts"), nullptr);
    EXPECT_NE(option_limit("flir-temperature", "--emissivity"), nullptr);
    EXPECT_EQ(option_limit("emissivity", "--emissivity"), nullptr);
    const OptionLimit* spp = option_limit("calibrate radiometric", "--spp");
    ASSERT_NE(spp, nullptr);
    EXPECT_EQ(spp->lo, 1);
    EXPECT_EQ(option_limit("planck", "--no-such-option"), nullptr);
}

TEST(ParseOptionValue, ALibraryErrorBecomesAUsageErrorNamingTheOption) {
    EXPECT_EQ(parse_option_value("--angles-deg", [] { return 2.5; }), 2.5);
    try {
        parse_option_value("--pattern", []() -> int { fail("'0,45': expected four angles"); });
        ADD_FAILURE() << "no OptionValueError";
    } catch (const OptionValueError& e) {
        EXPECT_EQ(e.option(), "--pattern");
        EXPECT_STREQ(e.what(), "'0,45': expected four angles");
    }
    // Anything that is not a tirpol::Error (a bug, not the user's text) passes through unchanged.
    EXPECT_THROW(parse_option_value("--pattern", []() -> int { throw std::logic_error("bug"); }),
                 std::logic_error);
}

}  // namespace
}  // namespace tirpol
