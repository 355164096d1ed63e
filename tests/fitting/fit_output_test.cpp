// What a fit writes: the material YAML is accepted by the materials loader (the format `tirpol
// emissivity` and the renderer read) and reproduces the fitted curve; the JSON report carries the
// documented keys; the plot is a PNG of the documented size.

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "synthetic_emissivity.h"
#include "test_support.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/fitting/fit_run.h"
#include "tirpol/fitting/microfacet_fit.h"
#include "tirpol/materials/material.h"
#include "tirpol/materials/microfacet.h"

namespace tirpol::fitting {
namespace {

using P = MicrofacetParameter;
using ::testing::HasSubstr;

struct Fitted {
    std::vector<EmissivityDataset> data;
    MicrofacetFitResult result;
};

// Fitted once for all tests of this file (the fit is deterministic).
const Fitted& fit_two_bands() {
    static const Fitted fitted = [] {
        const auto truth = test::paint_truth();
        std::vector<EmissivityDataset> data = {
            test::noisy(test::clean_dataset(truth, {0, 20, 40, 60, 75, 85}, 0.004, 0.002, 8.5), 3),
            test::noisy(test::clean_dataset(truth, {0, 20, 40, 60, 75, 85}, 0.004, 0.002, 11.0),
                        4)};
        MicrofacetFitOptions o;
        o.starts = 2;
        o.quadrature.order = 2;
        MicrofacetFitResult r = MicrofacetFitProblem(data, o).solve();
        return Fitted{data, r};
    }();
    return fitted;
}

TEST(FitOutput, MaterialYamlLoadsWithTheMaterialsLoaderAndKeepsTheValues) {
    const Fitted& f = fit_two_bands();
    tirpol::test::TempDir dir;
    const FitProvenance provenance{{"a.csv"}, "2026-11-22T17:00:00Z", "tirpol fit a.csv"};
    write_file_atomic(dir / "m.yaml", fitted_material_yaml("paint_fit", f.result, provenance));
    const materials::Material m = materials::load_material(dir / "m.yaml");
    EXPECT_EQ(m.name, "paint_fit");
    EXPECT_THAT(m.source, HasSubstr("a.csv"));
    EXPECT_THAT(m.source, HasSubstr("2026-11-22T17:00:00Z"));
    EXPECT_THAT(m.source, HasSubstr("chi2/dof"));
    EXPECT_THAT(m.notes, HasSubstr("sigma = "));
    EXPECT_THAT(m.notes, HasSubstr("(2σ)"));
    const auto* brdf = dynamic_cast<const materials::MicrofacetBrdf*>(m.brdf.get());
    ASSERT_NE(brdf, nullptr);
    for (std::size_t band = 0; band < 2; ++band) {
        const auto loaded = brdf->at(f.result.wavelengths_um[band]);
        const auto fitted = f.result.model_parameters(band);
        EXPECT_DOUBLE_EQ(loaded.n, fitted.n);
        EXPECT_DOUBLE_EQ(loaded.k, fitted.k);
        EXPECT_DOUBLE_EQ(loaded.sigma, fitted.sigma);
        EXPECT_DOUBLE_EQ(loaded.rho_d, fitted.rho_d);
        EXPECT_NEAR(loaded.omega_rad, fitted.omega_rad, 1e-12 * fitted.omega_rad);
    }
}

TEST(FitOutput, JsonReportHasTheDocumentedKeys) {
    const Fitted& f = fit_two_bands();
    const nlohmann::json j = fit_report_json(f.result, f.data, {{"a.csv"}, "date", "cmd"});
    for (const char* key :
         {"model", "data_files", "date_utc", "termination", "usable", "chi2", "dof", "reduced_chi2",
          "parameters", "correlation", "samples", "starts", "warnings", "covariance_scaled"})
        EXPECT_TRUE(j.contains(key)) << key;
    EXPECT_EQ(j["samples"].size(), 12u);
    EXPECT_EQ(j["starts"]["count"], 2);
    const auto& n = j["parameters"][0];
    EXPECT_EQ(n["name"], "n@8.5um");
    EXPECT_NEAR(n["interval_2sigma"][1].get<double>() - n["value"].get<double>(),
                2.0 * n["sigma"].get<double>(), 1e-12);
    EXPECT_EQ(j["correlation"]["names"].size(), 6u);
    const std::string text = fit_report_text(f.result, f.data);
    EXPECT_THAT(text, HasSubstr("chi2/dof"));
    EXPECT_THAT(text, HasSubstr("termination: CONVERGENCE"));
}

// A parameter near its bound (n = 0.30 ± 0.20 with n ∈ [0.14, 1.96]): value − 2σ = −0.10 is not a
// possible result, so every output reports [0.14, 0.70], the same as Python's intervals_2sigma.
TEST(FitOutput, IntervalsStopAtTheParameterBounds) {
    FittedParameter n;
    n.name = "n";
    n.value = 0.30;
    n.std_uncertainty = 0.20;
    n.lower = 0.14;
    n.upper = 1.96;
    const ParameterInterval near_bound = interval_2sigma(n);
    EXPECT_DOUBLE_EQ(near_bound.lower, 0.14);
    EXPECT_DOUBLE_EQ(near_bound.upper, 0.70);
    EXPECT_TRUE(near_bound.clipped);
    n.value = 1.0;  // well inside: value ± 2σ unchanged
    const ParameterInterval inside = interval_2sigma(n);
    EXPECT_DOUBLE_EQ(inside.lower, 0.60);
    EXPECT_DOUBLE_EQ(inside.upper, 1.40);
    EXPECT_FALSE(inside.clipped);

    Fitted f = fit_two_bands();
    FittedParameter& first = f.result.parameters[0];
    first.value = first.lower + 0.5 * first.std_uncertainty;  // within 2σ of the lower bound
    const nlohmann::json j = fit_report_json(f.result, f.data, {{"a.csv"}, "date", "cmd"});
    EXPECT_DOUBLE_EQ(j["parameters"][0]["interval_2sigma"][0].get<double>(), first.lower);
    EXPECT_THAT(fit_report_text(f.result, f.data),
                HasSubstr(fmt::format("[{:.6g}, {:.6g}]", first.lower,
                                      first.value + 2 * first.std_uncertainty)));
}

TEST(FitOutput, PlotIsAPngOfTheDocumentedSize) {
    const Fitted& f = fit_two_bands();
    tirpol::test::TempDir dir;
    write_fit_plot(dir / "fit.png", f.data, f.result, "test", {2});
    const std::string png = read_file(dir / "fit.png");
    ASSERT_GT(png.size(), 24u);
    EXPECT_EQ(png.substr(1, 3), "PNG");
    auto be32 = [&](std::size_t at) {
        return (static_cast<unsigned>(static_cast<unsigned char>(png[at])) << 24) |
               (static_cast<unsigned>(static_cast<unsigned char>(png[at + 1])) << 16) |
               (static_cast<unsigned>(static_cast<unsigned char>(png[at + 2])) << 8) |
               static_cast<unsigned>(static_cast<unsigned char>(png[at + 3]));
    };
    EXPECT_EQ(be32(16), 1000u);  // IHDR width
    EXPECT_EQ(be32(20), 920u);   // IHDR height: title band + two panels + axis labels
}

}  // namespace
}  // namespace tirpol::fitting
