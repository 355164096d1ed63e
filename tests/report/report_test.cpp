// The comparison report end to end on synthetic pairs with known noise and a known bias: the z
// statistic follows the normal law when the simulation is right and flags a real bias; numbers in
// report.json equal those returned; bad inputs fail clearly.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <nlohmann/json.hpp>

#include "error_of.h"
#include "synthetic_pair.h"
#include "test_support.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/config.h"
#include "tirpol/core/error.h"
#include "tirpol/core/interrupt_signals.h"
#include "tirpol/core/radiometry.h"
#include "tirpol/report/comparison_report.h"

using tirpol::test::error_of;

using namespace tirpol::report;
using ::testing::HasSubstr;

namespace {

/// The report of a synthetic pair with its regions and no registration, written into `dir`.
CompareResult compare_unregistered(const test::SyntheticPair& pair,
                                   const tirpol::test::TempDir& dir) {
    CompareOptions options;
    options.registration = RegistrationMethod::None;
    options.regions = parse_regions(tirpol::ConfigNode::parse(pair.regions_yaml, "rois.yaml"));
    return write_comparison_report(pair.measured, pair.simulated, options, dir.path());
}

const RegionResult& region(const CompareResult& r, const std::string& name) {
    for (const auto& region : r.regions)
        if (region.name == name) return region;
    throw std::runtime_error("no region " + name);
}

// Binomial standard deviation of a fraction p over n independent pixels.
double binomial_sd(double p, std::size_t n) {
    return std::sqrt(p * (1.0 - p) / static_cast<double>(n));
}

}  // namespace

TEST(ReportComparison, ZFollowsTheNormalLawWhenOnlyNoiseDiffers) {
    // Same scene, independent Gaussian noise of known σ in both images, variances given in the
    // channels: z ~ N(0, 1), so P(|z| > 2) = 4.55 % and P(|z| > 3) = 0.27 % within binomial
    // scatter.
    test::SyntheticPairOptions o;
    o.width = 256;
    o.height = 192;
    const auto pair = test::make_synthetic_pair(o);
    CompareOptions options;
    options.registration = RegistrationMethod::None;
    tirpol::test::TempDir dir;
    const CompareResult r =
        write_comparison_report(pair.measured, pair.simulated, options, dir.path());
    ASSERT_EQ(r.regions.size(), 1u);
    for (const Quantity quantity : kZQuantities) {
        const std::string& q = quantity_name(quantity);
        const ZStats& z = r.regions[0].z[quantity];
        ASSERT_EQ(z.pixel_count, 256u * 192u) << q;
        EXPECT_NEAR(z.fraction_above_2, kNormalTailAbove2,
                    4.0 * binomial_sd(kNormalTailAbove2, z.pixel_count))
            << q;
        EXPECT_NEAR(z.fraction_above_3, kNormalTailAbove3,
                    4.0 * binomial_sd(kNormalTailAbove3, z.pixel_count))
            << q;
        EXPECT_NEAR(z.rms, 1.0, 0.03) << q;
        EXPECT_TRUE(consistent_with_noise(z)) << q;
    }
    EXPECT_EQ(r.noise.s1.measured, "channel S1_std");
    EXPECT_EQ(r.noise.s1.simulated, "channel S1_var");
    EXPECT_NEAR(r.noise.s1.measured_sigma_median, std::sqrt(2.0) * o.measured_sigma, 1e-6);
    EXPECT_NEAR(r.noise.s0.simulated_sigma_median, o.simulated_sigma, 1e-6);
}

TEST(ReportComparison, ASetCancelFlagStopsTheComparisonBeforeItsRegistration) {
    const auto pair = test::make_synthetic_pair({});
    const std::atomic<bool> cancel{true};
    CompareOptions options;
    options.cancel = &cancel;
    EXPECT_THROW(compare(pair.measured, pair.simulated, options), tirpol::Cancelled);
}

TEST(ReportComparison, ARealBiasIsDetectedAndMeasured) {
    // Bias of S1 in the centre panel by one combined σ: P(|z| > 2) = P(N(1,1) > 2) + P(N(1,1) < −2)
    // = 0.1587 + 0.0013 = 16 %, far above 4.55 %; other regions stay consistent.
    test::SyntheticPairOptions o;
    const double sigma_total = std::sqrt(2.0 * o.measured_sigma * o.measured_sigma +
                                         o.simulated_sigma * o.simulated_sigma);
    o.s1_bias = sigma_total;
    const auto pair = test::make_synthetic_pair(o);
    tirpol::test::TempDir dir;
    const CompareResult r = compare_unregistered(pair, dir);
    const auto& centre = region(r, "panel_5");
    EXPECT_FALSE(consistent_with_noise(centre.z.s1));
    EXPECT_NEAR(centre.z.s1.fraction_above_2, 0.16, 0.05);
    EXPECT_NEAR(centre.stats.s1.bias, o.s1_bias,
                4.0 * sigma_total / std::sqrt(centre.stats.s1.pixel_count));
    EXPECT_TRUE(consistent_with_noise(region(r, "panel_1").z.s1));
    EXPECT_TRUE(consistent_with_noise(centre.z.s0));
    EXPECT_NEAR(region(r, "panel_1").stats.s1.bias, 0.0,
                4.0 * sigma_total / std::sqrt(region(r, "panel_1").stats.s1.pixel_count));
    // Verdicts per quantity: only S1 of the centre panel exceeds, and that decides the region. The
    // region-mean test sees the 1σ-per-pixel bias at t ≈ √n; its σ_mean is √(σ_m² + σ_s²)/√n.
    const auto& s1 = centre.verdicts.s1.mean;
    EXPECT_EQ(s1.verdict, Agreement::ExceedsNoise);
    EXPECT_NEAR(s1.combined.sigma, sigma_total / std::sqrt(static_cast<double>(s1.pixel_count)),
                1e-3 * s1.combined.sigma);
    EXPECT_GT(s1.t, 5.0);
    EXPECT_EQ(centre.verdicts.s0.mean.verdict, Agreement::ConsistentWithNoise);
    EXPECT_EQ(centre.verdicts.s2.mean.verdict, Agreement::ConsistentWithNoise);
    EXPECT_EQ(centre.verdict, Agreement::ExceedsNoise);
    EXPECT_EQ(region(r, "panel_1").verdict, Agreement::ConsistentWithNoise);
    // A bias that distorts nothing within the region leaves the per-pixel σ plausible.
    EXPECT_EQ(centre.verdicts.s1.sigma.verdict, SigmaCheck::Plausible);
}

TEST(ReportComparison, OverstatedMeasuredSigmaIsFlagged) {
    // The measurement states σ three times its real noise: z has RMS ≈ 1/3 … 0.5, almost never |z|
    // > 2; the fraction test alone would call it consistent.
    test::SyntheticPairOptions o;
    o.measured_uncertainty = false;
    o.simulated_variance = false;
    const auto pair = test::make_synthetic_pair(o);
    CompareOptions options;
    options.registration = RegistrationMethod::None;
    options.measured_frame_sigma = 3.0 * o.measured_sigma;
    tirpol::test::TempDir dir;
    const CompareResult r =
        write_comparison_report(pair.measured, pair.simulated, options, dir.path());
    const auto& all = r.regions.at(0);
    EXPECT_TRUE(consistent_with_noise(all.z.s0));
    // The σ diagnostic is separate from the agreement verdict: the means agree, the σ is too large.
    const auto& s0 = all.verdicts.s0;
    EXPECT_EQ(s0.sigma.verdict, SigmaCheck::Overestimated);
    EXPECT_LT(s0.sigma.sigma_factor, 0.5);
    EXPECT_EQ(s0.mean.verdict, Agreement::ConsistentWithNoise);
    EXPECT_EQ(all.verdict, Agreement::ConsistentWithNoise);
    const auto json = nlohmann::json::parse(tirpol::read_file(dir / "report.json"));
    EXPECT_EQ(json["regions"][0]["verdict"], "consistent with noise");
    EXPECT_EQ(json["regions"][0]["verdicts"]["S0"]["sigma_check"], "σ overestimated");
    EXPECT_THAT(tirpol::read_file(dir / "report.html"), HasSubstr("too large"));
}

TEST(ReportComparison, S0BiasInKelvinFollowsThePlanckSlopeOfTheBand) {
    // Measured S0 raised by dL/dT · 0.5 K at the simulated level: the bias in kelvin is 0.5 K
    // within its standard error, and that error is the radiance one divided by dL/dT.
    test::SyntheticPairOptions o;
    const auto pair0 = test::make_synthetic_pair(o);
    auto measured = pair0.measured;
    auto simulated = pair0.simulated;
    simulated.attributes()["band_um"] = std::vector<double>{8.0, 14.0};
    const tirpol::Band band(8.0, 14.0);
    CompareOptions options;
    options.registration = RegistrationMethod::None;
    options.regions = parse_regions(tirpol::ConfigNode::parse(pair0.regions_yaml, "rois.yaml"));
    // Panel 1 (k = 0) is uniform: S0 = 24 + ramp + 3 W/(m²·sr) ≈ 27.8.
    tirpol::test::TempDir dir;
    const CompareResult base = write_comparison_report(measured, simulated, options, dir / "base");
    const auto& p1 = region(base, "panel_1");
    ASSERT_TRUE(p1.s0_bias_k.has_value());
    const double t = band.brightness_temperature(p1.stats.s0.simulated_mean);
    EXPECT_NEAR(p1.s0_bias_k->temperature_k, t, 1e-9);
    EXPECT_NEAR(p1.s0_bias_k->radiance_dT, band.radiance_dT(t), 1e-12);
    const float offset = static_cast<float>(0.5 * band.radiance_dT(t));
    for (auto& v : measured.channel("S0")) v += offset;
    const CompareResult shifted =
        write_comparison_report(measured, simulated, options, dir / "shifted");
    const auto& k = *region(shifted, "panel_1").s0_bias_k;
    EXPECT_NEAR(k.bias_k - p1.s0_bias_k->bias_k, 0.5, 1e-3);
    EXPECT_NEAR(k.bias_k, 0.5, 4.0 * k.bias_sigma_k);
    EXPECT_NEAR(k.bias_sigma_k, region(shifted, "panel_1").stats.s0.bias_sigma / k.radiance_dT,
                1e-12);
    EXPECT_EQ(shifted.band_source, "band_um attribute of simulated");
    // Without a band the kelvin bias is absent and the report says why.
    simulated.attributes().erase("band_um");
    const CompareResult none = write_comparison_report(measured, simulated, options, dir / "none");
    EXPECT_FALSE(region(none, "panel_1").s0_bias_k.has_value());
    EXPECT_THAT(none.notes.back(), HasSubstr("not converted to kelvin"));
}

TEST(ReportComparison, AopStatisticsUsePolarizedPixelsOnly) {
    // Scene: panels have S1 ≈ −0.15 … −0.63 (AoP 90°), the background S1 = 0.02 with σ(S1) ≈ 0.078:
    // the panels count, the background is mostly left out.
    test::SyntheticPairOptions o;
    const auto pair = test::make_synthetic_pair(o);
    tirpol::test::TempDir dir;
    const CompareResult r = compare_unregistered(pair, dir);
    const auto& p9 = region(r, "panel_9").aop;
    EXPECT_GT(p9.pixel_count, p9.region_pixel_count * 9 / 10);
    EXPECT_NEAR(p9.measured_mean_deg, 90.0, 2.0);
    EXPECT_NEAR(p9.difference_mean_deg, 0.0, 1.0);
    const auto& bg = region(r, "background").aop;
    EXPECT_LT(bg.pixel_count, bg.region_pixel_count / 10);
}

TEST(ReportComparison, S1ContrastAgainstTheBackgroundMatchesTheScene) {
    // Scene (synthetic_pair.h): panel k adds −0.15 − 0.06 k to the background's S1 = 0.02, so the
    // contrast of panel 1 (k = 0) is −0.15 and of panel 5 (k = 4) −0.39 W/(m²·sr), in both images.
    test::SyntheticPairOptions o;
    o.shift_x_px = 2.3;
    o.shift_y_px = -1.4;
    const auto pair = test::make_synthetic_pair(o);
    CompareOptions options;  // automatic registration
    options.regions = parse_regions(tirpol::ConfigNode::parse(pair.regions_yaml, "rois.yaml"));
    tirpol::test::TempDir dir;
    const CompareResult r =
        write_comparison_report(pair.measured, pair.simulated, options, dir.path());
    EXPECT_LT(std::hypot(r.registration.residual_shift_px[0], r.registration.residual_shift_px[1]),
              0.5);
    for (const auto& [name, contrast] :
         {std::pair{"panel_1", -0.15}, std::pair{"panel_5", -0.39}}) {
        const auto& reg = region(r, name);
        ASSERT_TRUE(reg.s1_contrast_measured.has_value()) << name;
        EXPECT_NEAR(*reg.s1_contrast_measured, contrast, 0.01) << name;
        EXPECT_NEAR(*reg.s1_contrast_simulated, contrast, 0.01) << name;
    }
    EXPECT_NEAR(*region(r, "background").s1_contrast_measured, 0.0, 1e-12);

    // report.json holds the same numbers, and the page embeds every figure.
    const auto json = nlohmann::json::parse(tirpol::read_file(dir / "report.json"));
    EXPECT_EQ(json["measured"]["width"], 192);
    EXPECT_EQ(json["registration"]["method"], "auto");
    EXPECT_DOUBLE_EQ(json["regions"][1]["stats"]["S1"]["bias"].get<double>(),
                     r.regions[1].stats.s1.bias);
    EXPECT_DOUBLE_EQ(json["regions"][0]["s1_contrast"]["measured"].get<double>(),
                     *r.regions[0].s1_contrast_measured);
    EXPECT_DOUBLE_EQ(json["regions"][0]["z"]["all"]["fraction_above_2"].get<double>(),
                     r.regions[0].z_pooled.fraction_above_2);
    EXPECT_EQ(json["background"], "background");
    for (const auto& png : json["files"]["pngs"])
        EXPECT_TRUE(std::filesystem::exists(dir / png.get<std::string>())) << png;
    EXPECT_TRUE(std::filesystem::exists(dir / "comparison.exr"));
    const std::string html = tirpol::read_file(dir / "report.html");
    EXPECT_THAT(html, HasSubstr("<h2>Region statistics</h2>"));
    EXPECT_THAT(html, ::testing::Not(HasSubstr("<script")));
    EXPECT_THAT(html, ::testing::Not(HasSubstr("http")));
    std::size_t images = 0, embedded = 0;
    for (std::size_t at = html.find("<img "); at != std::string::npos;
         at = html.find("<img ", at + 1))
        ++images;
    for (std::size_t at = html.find("src=\"data:image/png;base64,"); at != std::string::npos;
         at = html.find("src=\"data:image/png;base64,", at + 1))
        ++embedded;
    EXPECT_GE(images, 6u);  // five Stokes panels, z panel
    EXPECT_EQ(images, embedded);
    // Plots are inline SVG, one per file written.
    std::size_t svgs = 0;
    for (std::size_t at = html.find("<svg "); at != std::string::npos;
         at = html.find("<svg ", at + 1))
        ++svgs;
    EXPECT_EQ(svgs, r.svgs.size());
    EXPECT_EQ(svgs, 10u);  // region overview, z histogram, 4 scatter plots, 4 difference histograms
}

TEST(ReportComparison, PlotsHaveNiceTicksAndKeepUnicodeNames) {
    // A region named in German with a snowflake: SVG text keeps it as written (Hershey fonts
    // dropped it).
    test::SyntheticPairOptions o;
    const auto pair = test::make_synthetic_pair(o);
    std::string yaml = pair.regions_yaml;
    yaml.replace(yaml.find("panel_1"), 7, "\"Schnee ❄ – Lack\"");
    CompareOptions options;
    options.registration = RegistrationMethod::None;
    options.regions = parse_regions(tirpol::ConfigNode::parse(yaml, "rois.yaml"));
    tirpol::test::TempDir dir;
    const CompareResult r =
        write_comparison_report(pair.measured, pair.simulated, options, dir.path());
    const std::string svg = tirpol::read_file(dir / "scatter_S0.svg");
    EXPECT_THAT(svg, HasSubstr(">Schnee ❄ – Lack</text>"));
    EXPECT_THAT(tirpol::read_file(dir / "report.html"), HasSubstr(">Schnee ❄ – Lack</text>"));
    // x tick labels (centred under the axis): equally spaced by 1, 2, 2.5 or 5 × 10^k, each printed
    // with no more digits than the step needs.
    std::vector<double> ticks;
    const std::string marker = "font-size=\"12\" text-anchor=\"middle\">";
    for (std::size_t at = svg.find(marker); at != std::string::npos;
         at = svg.find(marker, at + 1)) {
        std::string label = svg.substr(at + marker.size(), svg.find('<', at) - at - marker.size());
        if (label.rfind("−", 0) == 0) label = "-" + label.substr(std::string("−").size());
        ticks.push_back(std::stod(label));
        EXPECT_LE(label.size(), 7u) << label;
    }
    ASSERT_GE(ticks.size(), 3u);
    const double step = ticks[1] - ticks[0];
    const double mantissa = step / std::pow(10.0, std::floor(std::log10(step)));
    EXPECT_TRUE(std::abs(mantissa - 1) < 1e-9 || std::abs(mantissa - 2) < 1e-9 ||
                std::abs(mantissa - 2.5) < 1e-9 || std::abs(mantissa - 5) < 1e-9)
        << step;
    for (std::size_t i = 1; i < ticks.size(); ++i)
        EXPECT_NEAR(ticks[i] - ticks[i - 1], step, 1e-9 * step);
    for (double t : ticks) EXPECT_NEAR(std::remainder(t, step), 0.0, 1e-9 * step) << t;
    // Ticks lie within the data range of S0 (about 24 … 34 W/(m²·sr) in this scene).
    EXPECT_GT(ticks.front(), 20.0);
    EXPECT_LT(ticks.back(), 40.0);
}

TEST(ReportComparison, MeasuredNoiseFallsBackToUserSigmaFlatRegionOrImmerkaer) {
    test::SyntheticPairOptions o;
    o.measured_uncertainty = false;
    const auto pair = test::make_synthetic_pair(o);
    tirpol::test::TempDir dir;
    CompareOptions options;
    options.registration = RegistrationMethod::None;
    options.measured_frame_sigma = o.measured_sigma;
    auto r = write_comparison_report(pair.measured, pair.simulated, options, dir / "user");
    EXPECT_THAT(r.noise.s1.measured, HasSubstr("--measured-sigma"));
    EXPECT_NEAR(r.noise.s1.measured_sigma_median, std::sqrt(2.0) * o.measured_sigma,
                1e-6);  // eq 15
    EXPECT_TRUE(consistent_with_noise(r.regions[0].z_pooled));

    options.measured_frame_sigma.reset();
    options.regions = parse_regions(tirpol::ConfigNode::parse(pair.regions_yaml, "rois.yaml"));
    r = write_comparison_report(pair.measured, pair.simulated, options, dir / "flat");
    EXPECT_EQ(r.noise.s0.measured, "std of measured S0 in flat region 'background'");
    // The background has a gentle S0 gradient; S1 is flat there, so its std is the noise.
    EXPECT_NEAR(r.noise.s1.measured_sigma_median, std::sqrt(2.0) * o.measured_sigma,
                0.1 * o.measured_sigma);

    options.regions.reset();
    r = write_comparison_report(pair.measured, pair.simulated, options, dir / "immerkaer");
    EXPECT_THAT(r.noise.s2.measured, HasSubstr("Immerkær"));
    EXPECT_NEAR(r.noise.s2.measured_sigma_median, std::sqrt(2.0) * o.measured_sigma,
                0.15 * o.measured_sigma);
}

TEST(ReportComparison, MissingSimulationVarianceIsNotedNotFatal) {
    test::SyntheticPairOptions o;
    o.simulated_variance = false;
    const auto pair = test::make_synthetic_pair(o);
    tirpol::test::TempDir dir;
    CompareOptions options;
    options.registration = RegistrationMethod::None;
    const auto r = write_comparison_report(pair.measured, pair.simulated, options, dir.path());
    EXPECT_EQ(r.noise.s0.simulated, "none (σ_s = 0)");
    ASSERT_FALSE(r.notes.empty());
    EXPECT_THAT(r.notes[0], HasSubstr("no S0_var channel"));
}

TEST(ReportComparison, DegreesOfFreedomOfTheVariancesReachTheReport) {
    // A render's variance is estimated from its own replicates with R − 1 degrees of freedom (EXR
    // attribute variance_dof; docs/report.md); the z statistic then maps Student's t with the
    // Welch–Satterthwaite ν to the normal z of the same tail. The reader is told which ν were used:
    // the result, report.json and the noise table of report.html carry them, and they are the ones
    // the z used (stating ν = 12 pulls the region's RMS z below that of the same pair taken as
    // exact). ν = 12 is above kPerPixelVarianceDof, so the z use each pixel's own variance
    // (PooledVariance.* tests the pooling below it).
    const auto exact = test::make_synthetic_pair({});
    auto estimated = exact;
    estimated.simulated.attributes()["variance_dof"] = 12;
    CompareOptions options;
    options.registration = RegistrationMethod::None;
    tirpol::test::TempDir dir;
    const CompareResult r =
        write_comparison_report(estimated.measured, estimated.simulated, options, dir.path());
    const CompareResult r_exact = compare(exact.measured, exact.simulated, options).result;
    for (const Quantity q : kZQuantities) {
        const std::string& name = quantity_name(q);
        EXPECT_EQ(r.noise[q].simulated_dof, 12.0) << name;
        EXPECT_TRUE(std::isinf(r.noise[q].measured_dof)) << name;
        EXPECT_TRUE(std::isinf(r_exact.noise[q].simulated_dof)) << name;
        EXPECT_LT(r.regions[0].z[q].rms, r_exact.regions[0].z[q].rms) << name;
    }
    const auto json = nlohmann::json::parse(tirpol::read_file(dir / "report.json"));
    EXPECT_EQ(json["noise"]["S1"]["simulated_dof"].get<double>(), 12.0);
    EXPECT_TRUE(json["noise"]["S1"]["measured_dof"].is_null());
    const std::string html = tirpol::read_file(dir / "report.html");
    const std::size_t table = html.find("<caption>Noise used");
    ASSERT_NE(table, std::string::npos);
    const std::string noise_table = html.substr(table, html.find("</table>", table) - table);
    EXPECT_THAT(noise_table, HasSubstr("<th>ν_m</th>"));
    EXPECT_THAT(noise_table, HasSubstr("<th>ν_s</th>"));
    for (const Quantity quantity : kZQuantities) {
        const std::string& q = quantity_name(quantity);
        const std::size_t row = noise_table.find("<tr><td>" + q + "</td>");
        ASSERT_NE(row, std::string::npos) << q;
        const std::string cells = noise_table.substr(row, noise_table.find("</tr>", row) - row);
        EXPECT_THAT(cells, HasSubstr("<td>∞</td>")) << q;  // the measured σ channel: taken as exact
        EXPECT_THAT(cells, HasSubstr("<td>12</td>")) << q;  // the render's estimated variance
    }
}

TEST(ReportComparison, BadInputsFailClearly) {
    const auto pair = test::make_synthetic_pair({});
    tirpol::test::TempDir dir;
    CompareOptions options;
    options.measured_name = "M.exr";
    options.simulated_name = "S.exr";

    tirpol::Image partial(pair.measured.width(), pair.measured.height());
    partial.set_channel("S0", pair.measured.channel("S0"));
    partial.set_channel("S1", pair.measured.channel("S1"));
    auto msg =
        error_of([&] { write_comparison_report(partial, pair.simulated, options, dir.path()); });
    EXPECT_THAT(msg, HasSubstr("M.exr"));
    EXPECT_THAT(msg, HasSubstr("lacks channel S2"));
    EXPECT_THAT(msg, HasSubstr("channels present: S0, S1"));

    test::SyntheticPairOptions other;
    other.width = 100;
    other.height = 100;
    const auto square = test::make_synthetic_pair(other);
    msg = error_of(
        [&] { write_comparison_report(pair.measured, square.simulated, options, dir.path()); });
    EXPECT_THAT(msg, HasSubstr("give control points"));

    options.regions = parse_regions(tirpol::ConfigNode::parse(
        "regions:\n  - name: off_image\n    polygon: [[500, 10], [600, 10], [600, 50]]\n",
        "rois.yaml"));
    msg = error_of(
        [&] { write_comparison_report(pair.measured, pair.simulated, options, dir.path()); });
    EXPECT_THAT(msg, HasSubstr("rois.yaml:2"));
    EXPECT_THAT(msg, HasSubstr("outside the 192×144 measured image"));
    EXPECT_FALSE(
        std::filesystem::exists(dir / "report.html"));  // nothing written before inputs are checked
}
