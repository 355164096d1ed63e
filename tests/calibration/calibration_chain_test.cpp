// The calibration chain (calibration_chain.h): one ordered list of steps that every front end runs.
// On synthetic sessions with a planted truth (calibration/synthetic_session.h) the chain's
// products are bit-identical to the step functions called by hand in the same order, and the
// panel's planted ε (0.93, −0.035, 0.01) comes back within 2σ; steps run in list order, only when
// due, and a step that lacks its input names itself.

#include "tirpol/calibration/calibration_chain.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "test_support.h"
#include "tirpol/calibration/synthetic_session.h"
#include "tirpol/core/error.h"

namespace tirpol::calibration {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

class CalibrationChain : public testing::Test {
protected:
    static void SetUpTestSuite() {
        dir_ = new test::TempDir("tirpol-calibration-chain");
        write_synthetic_sessions(dir_->path(), SyntheticCamera{},
                                 synthetic_panel_scene(64, 48, kBand), kBand);
    }
    static void TearDownTestSuite() { delete dir_; }
    static std::filesystem::path root() { return dir_->path(); }

    /// The whole chain on the synthetic sessions: lab → polcal → scene → the panel's regions.
    static ChainInputs all_inputs() {
        ChainInputs in;
        in.band = kBand;
        in.blackbody_sessions = {root() / "lab"};
        in.polarimetric_session = root() / "polcal";
        in.scene_sessions = {root() / "scene"};
        in.rois = {panel_rois()};
        return in;
    }
    /// Reflector x 4..15, panel x 24..39 (synthetic_panel_scene at 64×48).
    static EmissivityRois panel_rois() {
        EmissivityRois rois;
        rois.reflector = {5, 10, 9, 28};
        rois.targets = {{"panel", {26, 12, 12, 24}, 45.0, 300.0, 0.05, std::nullopt}};
        return rois;
    }

    static inline const Band kBand{8.0, 14.0};
    static test::TempDir* dir_;
};
test::TempDir* CalibrationChain::dir_ = nullptr;

std::vector<std::string> step_names() {
    std::vector<std::string> names;
    for (const auto& s : calibration_steps()) names.emplace_back(s.name);
    return names;
}

TEST_F(CalibrationChain, StepsRunInTheOrderOfTheList) {
    EXPECT_THAT(step_names(), ElementsAre("radiometric", "polarimetric", "reduce", "emissivity"));
    std::vector<std::string> ran;
    run_calibration_chain(all_inputs(), {},
                          [&](const CalibrationStep& s) { ran.emplace_back(s.name); });
    EXPECT_EQ(ran, step_names());
}

TEST_F(CalibrationChain, ProductsAreThoseOfTheStepFunctionsCalledByHand) {
    const ChainProducts p = run_calibration_chain(all_inputs());
    const auto radiometric = calibrate_radiometric_session(root() / "lab", kBand);
    const auto polarimetric = calibrate_polarimetric_session(root() / "polcal", radiometric);
    const Image stokes = reduce_session(root() / "scene", radiometric, &polarimetric);
    const auto emissivity = extract_emissivity(stokes, panel_rois(), kBand);

    ASSERT_TRUE(p.radiometric && p.polarimetric);
    EXPECT_EQ(p.radiometric->gain, radiometric.gain);
    EXPECT_EQ(p.radiometric->offset, radiometric.offset);
    EXPECT_EQ(p.radiometric->bad, radiometric.bad);
    EXPECT_FALSE(p.quality);  // only with assess_quality
    EXPECT_EQ(p.polarimetric->analyzer_method, polarimetric.analyzer_method);
    EXPECT_EQ(p.polarimetric->wire_grid.at(45.0).tau, polarimetric.wire_grid.at(45.0).tau);
    EXPECT_EQ(p.polarimetric->wire_grid.at(45.0).background,
              polarimetric.wire_grid.at(45.0).background);
    ASSERT_EQ(p.stokes.size(), 1u);
    for (const auto& c : stokes.channel_names())
        EXPECT_EQ(p.stokes[0].channel(c), stokes.channel(c)) << c;
    ASSERT_EQ(p.emissivity.size(), 1u);
    ASSERT_EQ(p.emissivity[0].size(), 1u);
    const EmissivityResult& e = p.emissivity[0][0];
    EXPECT_EQ(e.eps_s0, emissivity[0].eps_s0);
    EXPECT_EQ(e.eps_s1, emissivity[0].eps_s1);
    EXPECT_EQ(e.eps_s2, emissivity[0].eps_s2);
    // The planted panel (write_synthetic_sessions: ε_S0 0.93, ε_S1 −0.035, ε_S2 0.01) within 2σ.
    EXPECT_NEAR(e.eps_s0, 0.93, std::max(2.0 * e.eps_s0_std, 0.005));
    EXPECT_NEAR(e.eps_s1, -0.035, std::max(2.0 * e.eps_s1_std, 0.002));
    EXPECT_NEAR(e.eps_s2, 0.01, std::max(2.0 * e.eps_s2_std, 0.002));
}

TEST_F(CalibrationChain, GivenProductsSkipTheirStepsAndAbsentInputsSkipTheirs) {
    const ChainProducts first = run_calibration_chain(all_inputs());
    // A calibration read from its file starts the chain at the reduction (`tirpol reduce`): the
    // ideal analyzer without a polarimetric calibration, as reduce_session gives it.
    ChainInputs scene_only;
    scene_only.scene_sessions = {root() / "scene"};
    ChainProducts given;
    given.radiometric = first.radiometric;
    std::vector<std::string> ran;
    const ChainProducts p = run_calibration_chain(
        scene_only, given, [&](const CalibrationStep& s) { ran.emplace_back(s.name); });
    EXPECT_THAT(ran, ElementsAre("reduce"));
    EXPECT_FALSE(p.polarimetric);
    EXPECT_EQ(p.stokes.at(0).channel("S1"),
              reduce_session(root() / "scene", *first.radiometric, nullptr).channel("S1"));
    // A Stokes image given (`extract-emissivity STOKES.exr`): only eq 17 runs.
    ChainInputs regions_only;
    regions_only.rois = {panel_rois()};
    ChainProducts stokes_given;
    stokes_given.stokes = first.stokes;
    ran.clear();
    const ChainProducts q = run_calibration_chain(
        regions_only, stokes_given, [&](const CalibrationStep& s) { ran.emplace_back(s.name); });
    EXPECT_THAT(ran, ElementsAre("emissivity"));
    EXPECT_EQ(q.emissivity.at(0).at(0).eps_s1, first.emissivity.at(0).at(0).eps_s1);
}

TEST_F(CalibrationChain, AStepThatLacksItsInputNamesItself) {
    auto error_of = [](const ChainInputs& in, ChainProducts given = {}) {
        try {
            run_calibration_chain(in, std::move(given));
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    ChainInputs scene_only;
    scene_only.scene_sessions = {root() / "scene"};
    EXPECT_THAT(error_of(scene_only), HasSubstr("step 'reduce': needs a radiometric calibration"));
    ChainInputs regions_only;
    regions_only.rois = {panel_rois()};
    EXPECT_THAT(error_of(regions_only), HasSubstr("step 'emissivity': needs Stokes images"));
    ChainInputs two_sets = regions_only;
    two_sets.rois.push_back(panel_rois());
    ChainProducts one_image;
    one_image.stokes = {synthetic_panel_scene(64, 48, kBand)};
    EXPECT_THAT(error_of(two_sets, one_image),
                HasSubstr("2 region sets for 1 Stokes images; expected 1 or 1"));
}

}  // namespace
}  // namespace tirpol::calibration
