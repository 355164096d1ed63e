// The parameter settings as users write them (--bound NAME=LOWER:UPPER, --fix NAME[=VALUE],
// --free NAME): each changes only the named parameter, and malformed items are refused with the
// item named.

#include <gtest/gtest.h>

#include <string>

#include "tirpol/core/error.h"
#include "tirpol/fitting/fit_run.h"

namespace tirpol::fitting {
namespace {

std::size_t index_of(MicrofacetParameter p) { return static_cast<std::size_t>(p); }

std::string error_of(void (*apply)(std::string_view, ParameterSettings&), std::string_view item) {
    ParameterSettings settings = default_parameter_settings();
    try {
        apply(item, settings);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

TEST(ParameterOptions, BoundSetsLowerAndUpperOfTheNamedParameterOnly) {
    ParameterSettings settings = default_parameter_settings();
    const ParameterSettings before = settings;
    apply_parameter_bound("sigma=0.05:0.8", settings);
    EXPECT_EQ(settings[index_of(MicrofacetParameter::sigma)].lower, 0.05);
    EXPECT_EQ(settings[index_of(MicrofacetParameter::sigma)].upper, 0.8);
    for (std::size_t i = 0; i < settings.size(); ++i) {
        if (i == index_of(MicrofacetParameter::sigma)) continue;
        EXPECT_EQ(settings[i].lower, before[i].lower) << parameter_name(MicrofacetParameter(i));
        EXPECT_EQ(settings[i].upper, before[i].upper) << parameter_name(MicrofacetParameter(i));
    }
    apply_parameter_bound("n=-1e1:2.5", settings);
    EXPECT_EQ(settings[index_of(MicrofacetParameter::n)].lower, -10.0);
}

TEST(ParameterOptions, FixHoldsAtTheGivenValueOrTheInitialOneAndFreeReleases) {
    ParameterSettings settings = default_parameter_settings();
    const double initial_k = settings[index_of(MicrofacetParameter::k)].initial;
    apply_parameter_fix("k", settings);
    EXPECT_TRUE(settings[index_of(MicrofacetParameter::k)].fixed);
    EXPECT_EQ(settings[index_of(MicrofacetParameter::k)].initial, initial_k);
    apply_parameter_fix("n=1.7", settings);
    EXPECT_TRUE(settings[index_of(MicrofacetParameter::n)].fixed);
    EXPECT_EQ(settings[index_of(MicrofacetParameter::n)].initial, 1.7);
    apply_parameter_free("n", settings);
    EXPECT_FALSE(settings[index_of(MicrofacetParameter::n)].fixed);
    EXPECT_TRUE(settings[index_of(MicrofacetParameter::k)].fixed);
}

TEST(ParameterOptions, MalformedItemsAreRefusedNamingTheItem) {
    EXPECT_NE(error_of(apply_parameter_bound, "sigma=0.05").find("expected NAME=LOWER:UPPER"),
              std::string::npos);
    EXPECT_NE(error_of(apply_parameter_bound, "sigma:0.05=0.8").find("sigma:0.05=0.8"),
              std::string::npos);
    EXPECT_NE(error_of(apply_parameter_bound, "sigma=0.05:nan")
                  .find("expected a finite number, got 'nan'"),
              std::string::npos);
    EXPECT_NE(error_of(apply_parameter_bound, "sigma=abc:1").find("\"abc\" is not a number"),
              std::string::npos);
    EXPECT_NE(
        error_of(apply_parameter_bound, "roughness=0:1").find("unknown micro-facet parameter"),
        std::string::npos);
    EXPECT_NE(error_of(apply_parameter_fix, "n=").find("is not a number"), std::string::npos);
    EXPECT_NE(error_of(apply_parameter_free, "eta").find("expected one of n, k, sigma"),
              std::string::npos);
}

}  // namespace
}  // namespace tirpol::fitting
