// `tirpol fit`'s library side from files: noise-free paint data written as CSV are fitted back to
// the paint (n, σ), the material YAML and its report name the files; parameter options that do not
// parse are errors of their option before any data file is read.

#include "tirpol/fitting/fit_run.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "synthetic_emissivity.h"
#include "test_support.h"
#include "tirpol/core/limits.h"
#include "tirpol/core/output_guard.h"
#include "tirpol/materials/material.h"

namespace tirpol::fitting {
namespace {

using ::testing::HasSubstr;
using P = MicrofacetParameter;

TEST(FitRun, PaintDataFromCsvFitBackAndTheMaterialFileIsWritten) {
    const tirpol::test::TempDir dir("fit_run");
    const auto truth = test::paint_truth();
    tirpol::test::write_text(
        dir / "paint.csv",
        emissivity_csv({test::clean_dataset(truth, test::fig1_angles(), 0.003, 0.002)}));
    FitRunOptions o;
    o.data = {(dir / "paint.csv").string()};
    o.starts = 4;
    o.output = (dir / "fitted.yaml").string();
    const FitRun run = run_fit(o);
    ASSERT_TRUE(run.result.usable) << run.result.termination;
    EXPECT_NEAR(run.result.get(P::n).value, truth.n, 0.01);
    EXPECT_NEAR(run.result.get(P::sigma).value, truth.sigma, 0.01);
    const materials::Material m = materials::load_material(o.output);
    EXPECT_EQ(m.name, "fitted");
    EXPECT_THAT(run.provenance.command, HasSubstr("--starts 4 --seed 1 --quadrature-order 4"));
    const nlohmann::json j = fit_run_json(run);
    EXPECT_EQ(j["material_file"], o.output);
    EXPECT_TRUE(j["plot_file"].is_null());
    EXPECT_THAT(fit_run_text(run), HasSubstr("material: " + o.output + "\n"));
}

TEST(FitRun, ParameterOptionsThatDoNotParseNameTheirOption) {
    for (const auto& [option, field] :
         {std::pair{"--bound", &FitRunOptions::bounds}, std::pair{"--free", &FitRunOptions::free},
          std::pair{"--fix", &FitRunOptions::fix}}) {
        FitRunOptions o;
        o.data = {"never-read.csv"};
        (o.*field) = {"no_such_parameter"};
        try {
            run_fit(o);
            FAIL() << option;
        } catch (const OptionValueError& e) {
            EXPECT_EQ(e.option(), option);
        }
    }
}

TEST(FitRun, OutputsAreCheckedAgainstTheDataBeforeAnyFileIsRead) {
    const tirpol::test::TempDir dir("fit_run_guard");
    FitRunOptions o;
    o.data = {(dir / "data.csv").string()};
    tirpol::test::write_text(o.data.front(), "not emissivity data");
    o.output = o.data.front();
    o.force = true;
    EXPECT_THROW(run_fit(o), OutputConflict);
    o.output = (dir / "fitted.yaml").string();
    tirpol::test::write_text(o.output, "kept");
    o.force = false;
    EXPECT_THROW(run_fit(o), OutputConflict);
    o.plot = o.data.front();
    o.force = true;
    EXPECT_THROW(run_fit(o), OutputConflict);
}

}  // namespace
}  // namespace tirpol::fitting
