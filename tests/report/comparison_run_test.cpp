// `tirpol compare` as one library call (report::run_comparison): option values are checked before
// any file is written, each refusal an OptionValueError naming its option (the CLI exits 2 with
// it); a valid run writes the report and records every input in the provenance.

#include <gtest/gtest.h>

#include <fstream>

#include "synthetic_pair.h"
#include "test_support.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/limits.h"
#include "tirpol/core/output_guard.h"
#include "tirpol/report/comparison_report.h"

namespace tirpol::report {
namespace {

struct PairFiles {
    tirpol::test::TempDir dir;
    ComparisonRunOptions options;
    PairFiles() {
        test::SyntheticPairOptions o;
        o.width = 96;
        o.height = 72;
        const test::SyntheticPair pair = test::make_synthetic_pair(o);
        write_exr(dir / "measured.exr", pair.measured);
        write_exr(dir / "simulated.exr", pair.simulated);
        options.measured = (dir / "measured.exr").string();
        options.simulated = (dir / "simulated.exr").string();
        options.output = (dir / "report").string();
        options.registration = "none";
    }
};

// The option an OptionValueError of run_comparison names; empty when it throws none (or another
// error).
std::string refused_option(const ComparisonRunOptions& options) {
    try {
        run_comparison(options);
    } catch (const OptionValueError& e) {
        return e.option();
    } catch (const Error&) {
        return "(not an option error)";
    }
    return "";
}

TEST(ComparisonRun, RefusesOutOfRangeValuesNamingTheOptionBeforeWritingAnything) {
    PairFiles f;
    auto with = [&](auto change) {
        ComparisonRunOptions o = f.options;
        change(o);
        return refused_option(o);
    };
    EXPECT_EQ(with([](auto& o) { o.measured_frame_sigma = 0.0; }), "--measured-sigma");
    EXPECT_EQ(with([](auto& o) { o.measured_frame_sigma = -1.0; }), "--measured-sigma");
    EXPECT_EQ(with([](auto& o) { o.gain_sigma_relative = 1.0; }), "--gain-sigma");
    EXPECT_EQ(with([](auto& o) { o.offset_sigma = -0.1; }), "--offset-sigma");
    EXPECT_EQ(with([](auto& o) { o.false_alarm = 0.5; }), "--false-alarm");
    EXPECT_EQ(with([](auto& o) { o.power = 0.5; }), "--power");
    EXPECT_EQ(with([](auto& o) { o.registration = "sideways"; }), "--registration");
    EXPECT_EQ(with([](auto& o) { o.registration = "control-points"; }), "--registration");
    EXPECT_EQ(with([](auto& o) { o.registration = "camera-model"; }), "--registration");
    EXPECT_FALSE(std::filesystem::exists(f.dir / "report")) << "written despite a refused option";
}

TEST(ComparisonRun, WritesTheReportAndRecordsEachInputInTheProvenance) {
    PairFiles f;
    f.options.tool_version = "tirpol test";
    f.options.command_line = "tirpol compare ...";
    const CompareResult r = run_comparison(f.options);
    EXPECT_TRUE(std::filesystem::exists(r.html));
    EXPECT_TRUE(std::filesystem::exists(r.json));
    EXPECT_EQ(r.provenance.tool_version, "tirpol test");
    EXPECT_EQ(r.provenance.command_line, "tirpol compare ...");
    ASSERT_EQ(r.provenance.inputs.size(), 2u);
    EXPECT_EQ(r.provenance.inputs[0].role, "measured");
    EXPECT_EQ(r.provenance.inputs[1].role, "simulated");
    EXPECT_EQ(r.provenance.inputs[0].sha256.size(), 64u);
    EXPECT_EQ(r.registration.method, RegistrationMethod::None);
}

TEST(ComparisonRun, KeepsAReportItDidNotWriteUnlessForced) {
    PairFiles f;
    std::filesystem::create_directories(f.dir / "report");
    tirpol::test::write_text(f.dir / "report" / "report.html", "someone else's report");
    EXPECT_THROW(run_comparison(f.options), OutputConflict);
    f.options.force = true;
    EXPECT_NE(run_comparison(f.options).html, std::filesystem::path());
}

}  // namespace
}  // namespace tirpol::report
