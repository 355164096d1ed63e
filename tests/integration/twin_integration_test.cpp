// Requires TIRPOL_WITH_ARAVIS (built only with that back end: cmake/TirpolBackends.cmake).
// The digital twin end to end at a tiny resolution: the measured Stokes of the flat black
// paint panel must agree with the truth render within the propagated uncertainties, the extracted
// polarized emissivity with the paint's model (materials::directional_emissivity) within the
// extraction's uncertainties, and the fitted n and σ with the paint's values within their fitted σ.
// The camera's lens and pose are recovered and the simulation, rendered through them,
// lands on the measured pixel grid without a warp.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <numbers>
#include <optional>

#include "test_support.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/camera_model.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/materials/emissivity.h"
#include "tirpol/materials/microfacet.h"
#include "tirpol/report/comparison_report.h"
#include "tirpol/twin/twin.h"

namespace tirpol::twin {
namespace {

TEST(DigitalTwin, RecoversStokesAndPaintParametersWithinUncertainties) {
    test::TempDir dir;
    TwinOptions options;
    options.out_dir = dir.path() / "twin";
    options.scene_file = test::source_dir() / "config/scenes/panels_night.yaml";
    options.width = 128;
    options.height = 96;
    options.spp = 4;
    options.frames_per_angle = 8;
    options.threads = 2;
    options.stage_protocol =
        StageProtocol::Elliptec;  // the demo uses APT: both protocols run end to end
    // The report at 5 % false alarm over its nine regions together (0.57 % per region): the test
    // below wants all eight regions rendered with their true materials consistent, which a correct
    // report at the default 5 % per region gives only 0.95⁸ = 66 % of the time.
    options.report_design.false_alarm_per_region = 1.0 - std::pow(0.95, 1.0 / 9.0);
    const TwinResult r = run_twin(options);
    std::printf("%s", twin_summary(r).c_str());

    // The camera really went over GigE Vision on loopback (no silent fallback).
    EXPECT_EQ(r.camera_transport.rfind("GigE Vision", 0), 0u) << r.camera_transport;
    EXPECT_NE(r.stage_description.find("Elliptec"), std::string::npos) << r.stage_description;
    ASSERT_EQ(r.sessions.size(), 4u);  // lab + three views

    // Measured Stokes of the target vs the truth render: within 4 propagated σ, and S1 < 0
    // (emission of a panel seen obliquely is polarized in the plane of emission, vertical in the
    // image).
    for (int c = 0; c < 3; ++c)
        EXPECT_LT(std::abs(r.target_stokes.measured[c] - r.target_stokes.truth[c]),
                  4.0 * r.target_stokes.std_error[c])
            << "S" << c << " measured " << r.target_stokes.measured[c] << " truth "
            << r.target_stokes.truth[c] << " σ " << r.target_stokes.std_error[c];
    EXPECT_LT(r.target_stokes.measured[1], 0.0);

    ASSERT_EQ(r.emissivity.size(), 3u);
    // The instrument chain: measured ε against eq 17 on the truth render, within 4 σ of both (their
    // common contact-temperature terms make this conservative for ε_S0, hardly for ε_S1). Against
    // the paint's table eq 17 itself is biased under a clear sky (the polarized reflection samples
    // the cold sky near zenith, the reflector the whole hemisphere): that bias is measured and
    // shown, and tests/twin/eq17_uniform_surroundings_test.cpp shows it vanishes when the
    // surroundings are uniform.
    for (const auto& e : r.emissivity) {
        EXPECT_LT(std::abs(e.eps_s0 - e.method_s0), 4.0 * std::hypot(e.eps_s0_std, e.method_s0_std))
            << "view angle " << e.view_angle_deg;
        EXPECT_LT(std::abs(e.eps_s1 - e.method_s1), 4.0 * std::hypot(e.eps_s1_std, e.method_s1_std))
            << "view angle " << e.view_angle_deg;
        EXPECT_LT(std::abs(e.method_s0 - e.true_s0), 4.0 * e.method_s0_std)
            << "view angle " << e.view_angle_deg;
        EXPECT_LT(e.method_s1, 0.0) << "view angle " << e.view_angle_deg;  // p-polarized emission
    }
    // Distinct view angles: the series constrains the fit.
    EXPECT_GT(r.emissivity.front().view_angle_deg - r.emissivity.back().view_angle_deg, 15.0);

    int free_parameters = 0;
    for (const auto& p : r.parameters) {
        if (p.fixed) continue;
        ++free_parameters;
        EXPECT_GT(p.std_uncertainty, 0.0) << p.name;
        EXPECT_LT(std::abs(p.fitted - p.truth), 4.0 * p.std_uncertainty)
            << p.name << " fitted " << p.fitted << " true " << p.truth;
    }
    EXPECT_EQ(free_parameters, 2);  // n and σ

    // The same paint fitted through the renderer (the sky colder at the zenith, the warm ground and
    // the reflector at 5 °C are rendered, not assumed uniform): within 2σ and 5 % of the truth with
    // χ²/dof ≤ 1.5, where eq 17's route is inconsistent with its own uncertainties. One seeded run
    // lands within 1σ with probability 0.68 per parameter (both: 0.47), so 1σ would test the seed;
    // whether the stated σ is right is asked over seeds by
    // RenderFit.PullsOfTheGlossyPaintOverIndependentSeedsAreUnitNormal.
    EXPECT_GT(r.reduced_chi2, 5.0) << "eq 17's route";
    ASSERT_TRUE(r.render_fit.usable);
    ASSERT_EQ(r.render_fit.parameters.size(), 2u);
    EXPECT_LE(r.render_fit.reduced_chi2, 1.5);
    for (const auto& p : r.render_fit.parameters) {
        EXPECT_LE(std::abs(p.fitted - p.truth), 2.0 * p.std_uncertainty)
            << p.name << " fitted " << p.fitted << " ± " << p.std_uncertainty;
        EXPECT_LE(std::abs(p.fitted - p.truth), 0.05 * p.truth) << p.name << " fitted " << p.fitted;
    }
    EXPECT_TRUE(std::filesystem::is_regular_file(r.fit_comparison));

    // Camera geometry (tests/twin checks the recovery at the demo's resolution): recovered within
    // its uncertainty, better than the nominal pose; the comparison used the recovered model, no
    // warp, and the residual misalignment measured from the images is a fraction of a pixel.
    EXPECT_NEAR(r.camera.lens.fx, r.camera.true_lens.fx, 3.0 * r.camera.lens.std_dev[0]);
    EXPECT_NEAR(r.camera.lens.cx, r.camera.true_lens.cx, 3.0 * r.camera.lens.std_dev[2]);
    EXPECT_LT(r.camera.position_error_m, r.camera.nominal_position_error_m);
    EXPECT_EQ(r.registration.method, report::RegistrationMethod::CameraModel);
    EXPECT_EQ(r.registration.model, "identity");
    // Phase correlation of two noisy renders reads a few tenths of a pixel even for the same camera
    // (0.40 px with the truth camera itself at 160×120, 8 spp: docs/twin.md); a pixel would be a
    // real error.
    EXPECT_LT(std::hypot(r.registration.residual_shift_px[0], r.registration.residual_shift_px[1]),
              0.5);

    EXPECT_TRUE(std::filesystem::is_regular_file(r.report_html));
    EXPECT_TRUE(std::filesystem::is_regular_file(r.fitted_material));
    // In the report, the fitted paint's panel agrees with the measurement within the stated noise.
    ASSERT_EQ(r.regions.size(), 9u);  // the nine panels
    const auto paint = std::find_if(r.regions.begin(), r.regions.end(),
                                    [](const auto& g) { return g.name == "flat_black_paint"; });
    ASSERT_NE(paint, r.regions.end());
    EXPECT_NE(paint->verdict, report::Agreement::NoData);
    // The panels whose material the simulation has right agree within the noise (the fitted paint's
    // own region carries eq 17's method bias, which the report may rightly flag: docs/twin.md).
    for (const auto& g : r.regions) {
        if (g.name != "flat_black_paint") {
            EXPECT_EQ(g.verdict, report::Agreement::ConsistentWithNoise) << g.name;
        }
    }
    // The blackbody set-points bracket the scene: no pixel is extrapolated, and the Summary says
    // so.
    EXPECT_TRUE(r.blackbody.limitation.empty()) << r.blackbody.limitation;
    EXPECT_EQ(r.calibration_outside_fraction, 0.0);
    EXPECT_NE(
        r.report_summary.find("Every measured pixel lies inside the blackbody calibration range"),
        std::string::npos)
        << r.report_summary;

    // The report is repeatable from the files it names: `tirpol compare` on the measured and
    // simulated EXRs, the regions YAML and the camera model give the same table (the simulated
    // variance channels carry the σ used).
    const auto json = nlohmann::json::parse(read_file(r.report_html.parent_path() / "report.json"));
    report::CompareOptions co;
    co.registration = report::RegistrationMethod::CameraModel;
    co.camera_model = read_camera_model(r.camera.lens_file);
    co.camera_model_name = r.camera.lens_file.string();
    co.regions = report::load_regions(r.report_regions);
    // The report's own test design (this twin runs at 5 % over nine regions, not the default 5 %
    // per region): with another design a region between the two critical values reads otherwise.
    co.design.false_alarm_per_region = json["design"]["false_alarm_per_region"].get<double>();
    co.design.power = json["design"]["power"].get<double>();
    const report::Comparison again =
        report::compare(read_exr(r.measured_exr), read_exr(r.simulated_exr), co);
    ASSERT_EQ(again.result.regions.size(), json["regions"].size());
    for (std::size_t i = 0; i < again.result.regions.size(); ++i) {
        const auto& region = again.result.regions[i];
        const auto& jr = json["regions"][i];
        EXPECT_EQ(region.name, jr["name"]);
        for (const report::Quantity quantity : report::kZQuantities) {
            const std::string& q = report::quantity_name(quantity);
            // report.json prints doubles round-trip exactly; EXR planes are float, as in memory.
            EXPECT_DOUBLE_EQ(region.z[quantity].fraction_above_2,
                             jr["z"][q]["fraction_above_2"].get<double>())
                << region.name << " " << q;
            EXPECT_DOUBLE_EQ(region.z[quantity].rms, jr["z"][q]["rms"].get<double>())
                << region.name << " " << q;
            EXPECT_DOUBLE_EQ(region.stats[quantity].bias, jr["stats"][q]["bias"].get<double>())
                << region.name << " " << q;
        }
        EXPECT_EQ(report::to_string(region.verdict), jr["verdict"]) << region.name;
    }
    // The provenance names those files, relative to the report's folder, with their checksums.
    const auto& inputs = json["provenance"]["inputs"];
    ASSERT_EQ(inputs.size(), 5u);
    const auto report_dir = r.report_html.parent_path();
    EXPECT_EQ(inputs[1]["path"], report::path_relative_to(r.simulated_exr, report_dir).string());
    EXPECT_EQ(inputs[4]["path"], report::path_relative_to(r.fit_comparison, report_dir).string());
    EXPECT_TRUE(
        std::filesystem::is_regular_file(report_dir / inputs[1]["path"].get<std::string>()));
    EXPECT_EQ(inputs[1]["sha256"], report::sha256_hex(read_file(r.simulated_exr)));
}

/// The twin at the size of the tests, compared with a render of the scene file's own materials: the
/// only model error is what `perturb` changes in the truth. 16 samples per pixel: one point in each
/// of the renderer's 16 replicates, so each pixel's render σ has 15 degrees of freedom. The report
/// is designed for a 5 % false-alarm rate over its nine regions together (Šidák: 0.57 % per
/// region), so that "no region flagged" and "only the perturbed region flagged" are what a correct
/// report gives 95 % of the time over noise realisations, not the 63 % of the per-region default (1
/// − 0.95⁹).
/// TIRPOL_TWIN_TEST_SEED (a non-negative integer), when set: the report tests' twin on other
/// noise realisations (TwinOptions::seed), to see how Σt² scatters from run to run (docs/twin.md).
std::optional<std::uint64_t> seed_knob() {
    const char* text = std::getenv("TIRPOL_TWIN_TEST_SEED");
    if (!text) return std::nullopt;
    char* end = nullptr;
    const unsigned long long value = std::strtoull(text, &end, 10);
    if (end == text || *end != '\0') {
        ADD_FAILURE() << "TIRPOL_TWIN_TEST_SEED='" << text << "': expected a non-negative integer";
        return std::nullopt;
    }
    return value;
}

TwinOptions model_check_options(const std::filesystem::path& out) {
    TwinOptions options;
    options.seed = seed_knob();
    options.out_dir = out;
    options.scene_file = test::source_dir() / "config/scenes/panels_night.yaml";
    options.width = 128;
    options.height = 96;
    options.spp = 16;
    options.frames_per_angle = 8;
    options.threads = 2;
    options.render_fitted_target = false;
    options.report_design.false_alarm_per_region = 1.0 - std::pow(0.95, 1.0 / 9.0);
    return options;
}

TEST(DigitalTwin, ReportSeesNoDifferenceWhereThereIsNone) {
    // Truth unchanged, simulation with the same materials: every panel "consistent with noise" (a
    // correct report false-alarms somewhere with probability 5 % by design; the seeds are fixed,
    // and MeanDifferenceTest.FalseAlarmRate… checks the rate itself over 4000 synthetic regions).
    test::TempDir dir;
    const TwinResult r = run_twin(model_check_options(dir.path() / "twin"));
    std::printf("%s", twin_summary(r).c_str());
    ASSERT_EQ(r.regions.size(), 9u);
    for (const auto& g : r.regions)
        EXPECT_EQ(g.verdict, report::Agreement::ConsistentWithNoise) << g.name;
    // "Consistent" alone would also hold for a σ that is too large (the conservative render
    // variance this report once had: σ 2.4× too large), so the region-mean t must also scatter as a
    // unit normal. Σt² over the 27 tests (9 regions × S0, S1, S2) follows χ²₂₇ when every σ_mean is
    // right; its 0.1 % and 99.9 % quantiles are 9.80 and 55.48 (NIST/SEMATECH e-Handbook
    // §1.3.6.7.4). σ 2.4× too large gives E[Σt²] = 27/2.4² = 4.7; σ 1.5× too small, 61.
    // Per quantity: t, the σ of the region mean from the measurement, the render (truth and
    // comparison) and the registration, and the per-pixel z scatter's σ factor, to tell which σ
    // term a Σt² far from 27 comes from.
    double sum_t2 = 0.0;
    int tests = 0;
    for (const auto& g : r.regions) {
        std::printf("  %-24s", g.name.c_str());
        for (const auto& q : g.quantities) {
            sum_t2 += q.mean.t * q.mean.t;
            ++tests;
            std::printf(" | t %+5.2f σ meas %.2e sim %.2e reg %.2e z×%.2f", q.mean.t,
                        q.mean.measured_independent.sigma, q.mean.simulated.sigma,
                        q.mean.registration.sigma, q.sigma.sigma_factor);
        }
        std::printf("\n");
    }
    ASSERT_EQ(tests, 27);
    std::printf(
        "  sum of t^2 over the 27 region-mean tests: %.2f (chi2_27: mean 27, 0.1%%-99.9%% "
        "9.80-55.48)\n",
        sum_t2);
    EXPECT_GT(sum_t2, 9.80);
    EXPECT_LT(sum_t2, 55.48);
}

TEST(DigitalTwin, ReportFlagsThePerturbedPanelAndOnlyIt) {
    // The truth's glossy black paint has n 0.1 lower than the model the simulation uses (1.45
    // instead of 1.55). Lower n weakens the Fresnel reflection: the paint emits more (ε_S0 +0.016
    // at 58°, smooth Fresnel) and less polarized (ε_S1, the plane-of-emission polarization, −0.090
    // → −0.074). Both changes are multiplied by the contrast between the panel's emission and the
    // sky it reflects, which for these panels at 58° is only ~6 W/(m²·sr) (the flat black paint's
    // S1/ε_S1, printed): ΔS0 ≈ ΔS1 ≈ 0.1 W/(m²·sr). In S1 that is several times the region's
    // detectable bias at this size; in S0 the render's Monte Carlo noise (the sky sampled in
    // reflection) makes the detectable bias ~0.45, so S1 is where the report must see it
    // (docs/report.md, "what the twin detects").
    test::TempDir dir;
    TwinOptions options = model_check_options(dir.path() / "twin");
    materials::MicrofacetParameters model_paint, true_paint;
    options.perturb_truth = [&](simulation::Scene& scene) {
        for (auto& m : scene.materials) {
            if (m.name != "glossy_black_paint") continue;
            const auto* micro = dynamic_cast<const materials::MicrofacetBrdf*>(m.brdf.get());
            ASSERT_NE(micro, nullptr);
            model_paint = micro->spectral_parameters();
            true_paint = model_paint;
            true_paint.index = materials::RefractiveIndexTable::constant({1.45, 0.1});
            m.brdf = std::make_shared<materials::MicrofacetBrdf>(true_paint);
        }
    };
    const TwinResult r = run_twin(options);
    std::printf("%s", twin_summary(r).c_str());
    ASSERT_EQ(r.regions.size(), 9u);
    for (const auto& g : r.regions) {
        const report::Agreement expected = g.name == "glossy_black_paint"
                                               ? report::Agreement::ExceedsNoise
                                               : report::Agreement::ConsistentWithNoise;
        EXPECT_EQ(g.verdict, expected) << g.name;
    }
    const auto glossy = std::find_if(r.regions.begin(), r.regions.end(),
                                     [](const auto& g) { return g.name == "glossy_black_paint"; });
    ASSERT_NE(glossy, r.regions.end());
    const report::MeanDifferenceTest& s1 = glossy->quantities[1].mean;
    EXPECT_EQ(s1.verdict, report::Agreement::ExceedsNoise);
    EXPECT_GT(s1.difference, s1.detectable_bias);  // resolved, not a marginal call
    // The summary names the region and its S1 difference (S0 may be named too: n − 0.1 also changes
    // ε_S0).
    const auto named = r.report_summary.find("glossy_black_paint in ");
    ASSERT_NE(named, std::string::npos) << r.report_summary;
    EXPECT_NE(r.report_summary.find("S1 by +", named), std::string::npos) << r.report_summary;

    // The size of the difference is the physics': Δε_S1 of the paint model between the two indices
    // at the flat black panel's view angle (the glossy panel sits beside it, same tilt and
    // temperature), times that panel's contrast C = S1 / ε_S1 (truth render S1 over the paint's
    // ε_S1). The glossy paint reflects the sky near its specular direction, the rough flat paint a
    // wider cone, so C differs between them: within 40 %.
    ASSERT_FALSE(r.emissivity.empty());
    const TwinEmissivity& e = r.emissivity.front();
    const double cos_view = std::cos(e.view_angle_deg * std::numbers::pi / 180.0);
    const double model_s1 = materials::directional_emissivity(
        materials::MicrofacetBrdf(model_paint), cos_view, 10.0)[1];
    const double true_s1 =
        materials::directional_emissivity(materials::MicrofacetBrdf(true_paint), cos_view, 10.0)[1];
    const double contrast = r.target_stokes.truth[1] / e.true_s1;
    const double expected_s1 = (true_s1 - model_s1) * contrast;
    std::printf(
        "  glossy black S1: measured - simulated %+.4f +- %.4f, expected (eps_S1 %.4f -> %.4f at "
        "%.1f deg) x "
        "C %.2f = %+.4f; S0 %+.4f +- %.4f (detectable %.3f)\n",
        s1.difference, s1.combined.sigma, model_s1, true_s1, e.view_angle_deg, contrast,
        expected_s1, glossy->quantities[0].mean.difference,
        glossy->quantities[0].mean.combined.sigma, glossy->quantities[0].mean.detectable_bias);
    EXPECT_GT(expected_s1, 0.0);  // less polarized emission: S1 (< 0) moves towards 0
    EXPECT_NEAR(s1.difference, expected_s1, 0.4 * expected_s1);
}

TEST(DigitalTwin, UnknownTargetIsAnErrorNamingItAndTheScene) {
    test::TempDir dir;
    TwinOptions options;
    options.out_dir = dir.path() / "twin";
    options.scene_file = test::source_dir() / "config/scenes/panels_night.yaml";
    options.target = "panel_no_such_paint";
    try {
        run_twin(options);
        FAIL() << "expected tirpol::Error";
    } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("digital twin, set-up stage"), std::string::npos) << message;
        EXPECT_NE(message.find("no object named 'panel_no_such_paint'"), std::string::npos)
            << message;
        EXPECT_NE(message.find("panels_night.yaml"), std::string::npos) << message;
        EXPECT_NE(message.find("panel_flat_black_paint"), std::string::npos)
            << message;  // lists the objects
    }
}

}  // namespace
}  // namespace tirpol::twin
