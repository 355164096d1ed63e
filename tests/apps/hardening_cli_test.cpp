// The CLI never prints inf/nan with exit 0 and always writes valid UTF-8 JSON (before: `planck
// --temperature-k 1e308` printed inf and -nan; a non-UTF-8 EXR attribute made `info --json` fail
// with json type_error 316). Exit code 1 is tirpol::Error (bad input), as in docs/cli.md.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "test_support.h"

namespace {

using tirpol::test::CliRun;
using tirpol::test::run_cli;

TEST(HardeningCli, PlanckRefusesTemperaturesOutsideThePhysicalRange) {
    for (const char* t : {"1e308", "0.5", "20000"}) {
        const CliRun r = run_cli(std::string("planck --temperature-k ") + t + " --band-um 8 14");
        EXPECT_EQ(r.exit_code, 2) << r.out;  // a value outside the option's range is a usage error
        EXPECT_THAT(r.out, testing::HasSubstr(std::string("--temperature-k: ") + t +
                                              " is outside [1, 10000]"))
            << t;
        // Words, not substrings: the usage message ends "Run with --help for more information".
        EXPECT_THAT(r.out, testing::Not(testing::ContainsRegex("(^|[^a-z])(inf|nan)([^a-z]|$)")));
    }
}

TEST(HardeningCli, InfoJsonOfNonUtf8AttributeIsValidJson) {
    const auto exr =
        tirpol::test::source_dir() / "tests/data/fuzz-regressions/exr/non_utf8_attribute.exr";
    const CliRun r = run_cli("info --json " + exr.string(), false);
    ASSERT_EQ(r.exit_code, 0) << r.out;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["attributes"]["note"],
              "caf\xEF\xBF\xBD \xEF\xBF\xBD\xEF\xBF\xBD");  // U+FFFD per invalid byte
}

TEST(HardeningCli, HugeDeclaredExrIsAClearErrorNotAnAllocation) {
    const auto exr =
        tirpol::test::source_dir() / "tests/data/fuzz-regressions/exr/declares_40000x40000.exr";
    const CliRun r = run_cli("info " + exr.string());
    EXPECT_EQ(r.exit_code, 1) << r.out;
    EXPECT_THAT(r.out, testing::HasSubstr("16384"));
    EXPECT_THAT(r.out, testing::Not(testing::HasSubstr("bad_alloc")));
}

}  // namespace
