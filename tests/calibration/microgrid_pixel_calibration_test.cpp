// Per-pixel analyzer calibration of a microgrid camera (Powell & Gruev 2013): a simulated camera
// with planted per-pixel axis, diattenuation, transmission and background spreads, calibrated from
// flat fields through a reference polarizer, must recover the planted parameters and reduce a
// uniform polarized field to within 0.2 % DoLP RMS (the figure of the issue), where ideal-analyzer
// reduction shows the planted spread.

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <random>

#include "microgrid_accuracy.h"
#include "tirpol/calibration/microgrid_session.h"
#include "tirpol/calibration/microgrid_stokes.h"
#include "tirpol/core/error.h"

namespace tirpol::calibration {
namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;

/// A microgrid camera whose every pixel has its own analyzer (truth for the test).
struct PlantedCamera {
    int width = 32, height = 24;
    std::vector<double> axis_deg, diattenuation, transmission, background;

    PlantedCamera(const MicrogridPattern& pattern, std::uint32_t seed) {
        std::mt19937 rng(seed);
        std::normal_distribution<double> axis_error(0.0, 2.0);
        std::uniform_real_distribution<double> d(0.85, 0.99), t(0.8, 1.2), b(0.0, 5.0);
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                axis_deg.push_back(pattern.angle_at_pixel_deg(x, y) + axis_error(rng));
                diattenuation.push_back(d(rng));
                transmission.push_back(t(rng));
                background.push_back(b(rng));
            }
    }
    std::vector<float> image(const Eigen::Vector3d& s, double noise_sigma,
                             std::mt19937& rng) const {
        std::normal_distribution<double> noise(0.0, noise_sigma);
        std::vector<float> frame(axis_deg.size());
        for (std::size_t i = 0; i < frame.size(); ++i) {
            const double two_theta = 2.0 * axis_deg[i] * kDegToRad;
            frame[i] =
                static_cast<float>(0.5 * transmission[i] *
                                       (s(0) + diattenuation[i] * (s(1) * std::cos(two_theta) +
                                                                   s(2) * std::sin(two_theta))) +
                                   background[i] + (noise_sigma > 0.0 ? noise(rng) : 0.0));
        }
        return frame;
    }
};

/// A blackbody of radiance L seen through an ideal reference polarizer at φ: S = ½L(1, cos 2φ, sin
/// 2φ); at 8 angles and two radiances (the second separates the background from the gain).
std::vector<MicrogridFlatField> flat_fields(const PlantedCamera& camera, double noise_sigma,
                                            std::mt19937& rng) {
    std::vector<MicrogridFlatField> fields;
    for (double radiance : {200.0, 100.0})
        for (int k = 0; k < 8; ++k) {
            const double two_phi = 2.0 * 22.5 * k * kDegToRad;
            const Eigen::Vector3d s(0.5 * radiance, 0.5 * radiance * std::cos(two_phi),
                                    0.5 * radiance * std::sin(two_phi));
            fields.push_back({s, camera.image(s, noise_sigma, rng)});
        }
    return fields;
}

double dolp_rms_error(const Image& stokes, double truth) {
    double sum = 0.0;
    for (float v : stokes.channel("DoLP")) sum += (v - truth) * (v - truth);
    return std::sqrt(sum / static_cast<double>(stokes.pixel_count()));
}

TEST(MicrogridPixelCalibration, RecoversPlantedAnalyzersExactlyWithoutNoise) {
    const MicrogridPattern sony = MicrogridPattern::sony_imx250mzr();
    const PlantedCamera camera(sony, 7);
    std::mt19937 rng(1);
    const MicrogridPixelCalibration cal =
        calibrate_microgrid_pixels(flat_fields(camera, 0.0, rng), camera.width, camera.height);
    EXPECT_LT(cal.fit_rms, 1e-3);
    for (std::size_t i = 0; i < camera.axis_deg.size(); ++i) {
        ASSERT_NEAR(cal.transmission(i), camera.transmission[i], 1e-4);
        ASSERT_NEAR(cal.diattenuation(i), camera.diattenuation[i], 1e-4);
        const double planted_axis = std::fmod(camera.axis_deg[i] + 180.0, 180.0);
        double diff = std::abs(cal.axis_angle_deg(i) - planted_axis);
        diff = std::min(diff, 180.0 - diff);
        ASSERT_LT(diff, 0.01) << i;
        ASSERT_NEAR(cal.background[i], camera.background[i], 1e-2);
    }
    // The calibration survives its EXR form.
    const MicrogridPixelCalibration back = MicrogridPixelCalibration::from_image(cal.to_image());
    EXPECT_EQ(back.analysis[1], cal.analysis[1]);
    EXPECT_EQ(back.background, cal.background);
}

TEST(MicrogridPixelCalibration,
     PerPixelReductionMeetsTwoTenthsPercentDolpWhereIdealAnalyzersDoNot) {
    // A uniform flat field of DoLP 0.3 at AoP 30°; calibration flat fields with noise σ = 0.05
    // counts (frame means) on ~100 counts per analyzer.
    const MicrogridPattern sony = MicrogridPattern::sony_imx250mzr();
    const PlantedCamera camera(sony, 11);
    std::mt19937 rng(2);
    const MicrogridPixelCalibration cal =
        calibrate_microgrid_pixels(flat_fields(camera, 0.05, rng), camera.width, camera.height);
    const double dolp = 0.3;
    const Eigen::Vector3d scene(300.0, 300.0 * dolp * std::cos(60.0 * kDegToRad),
                                300.0 * dolp * std::sin(60.0 * kDegToRad));
    const std::vector<float> frame = camera.image(scene, 0.0, rng);

    const Image per_pixel = reduce_microgrid_per_pixel(frame, cal);
    EXPECT_EQ(per_pixel.width(), camera.width / 2);
    EXPECT_EQ(std::get<int>(per_pixel.attributes().at("singular_cells")), 0);
    const double per_pixel_error = dolp_rms_error(per_pixel, dolp);
    EXPECT_LT(per_pixel_error, 0.002);

    MicrogridReductionOptions ideal;
    ideal.method = DemosaicMethod::SuperPixel;
    ideal.reduction.project_to_realizable = false;
    const double ideal_error =
        dolp_rms_error(reduce_microgrid(frame, camera.width, camera.height, sony, ideal), dolp);
    EXPECT_GT(ideal_error, 0.01);
    EXPECT_GT(ideal_error, 10.0 * per_pixel_error);
    std::printf(
        "DoLP RMS error on a uniform DoLP 0.3 field: ideal analyzers %.4f, per-pixel calibration "
        "%.5f\n",
        ideal_error, per_pixel_error);
}

/// The per-super-pixel least squares solved directly, cell by cell (QR of the cell's 4×3 W with a
/// bad pixel's row zero): the definition MicrogridPixelReducer precomputes.
std::array<double, 3> solve_cell_directly(std::span<const float> mosaic,
                                          const MicrogridPixelCalibration& c, int cx, int cy) {
    Eigen::Matrix<double, 4, 3> w = Eigen::Matrix<double, 4, 3>::Zero();
    Eigen::Vector4d signal = Eigen::Vector4d::Zero();
    for (int k = 0; k < 4; ++k) {
        const auto i = static_cast<std::size_t>((2 * cy + (k >> 1)) * c.width + 2 * cx + (k & 1));
        if (c.is_bad(i)) continue;
        for (std::size_t m = 0; m < 3; ++m) w(k, static_cast<Eigen::Index>(m)) = c.analysis[m][i];
        signal(k) = static_cast<double>(mosaic[i]) - c.background[i];
    }
    const Eigen::Vector3d s = w.colPivHouseholderQr().solve(signal);
    return {s(0), s(1), s(2)};
}

TEST(MicrogridPixelCalibration, PreparedReducerEqualsTheDirectPerCellLeastSquares) {
    // A planted camera with bad pixels (one of them NaN in the frame), a cell with two bad pixels
    // (singular: NaN) and a random, partly unrealizable frame.
    const MicrogridPattern sony = MicrogridPattern::sony_imx250mzr();
    const PlantedCamera camera(sony, 21);
    std::mt19937 rng(22);
    MicrogridPixelCalibration cal =
        calibrate_microgrid_pixels(flat_fields(camera, 0.05, rng), camera.width, camera.height);
    const auto n = static_cast<std::size_t>(camera.width * camera.height);
    cal.bad.assign(n, 0.0f);
    cal.bad[static_cast<std::size_t>(3 * camera.width + 7)] = 1.0f;   // cell (3, 1)
    cal.bad[static_cast<std::size_t>(10 * camera.width + 4)] = 2.0f;  // cell (2, 5): singular
    cal.bad[static_cast<std::size_t>(11 * camera.width + 5)] = 2.0f;
    std::uniform_real_distribution<double> counts(20.0, 400.0);
    for (int frame_kind = 0; frame_kind < 2; ++frame_kind) {
        std::vector<float> frame =
            frame_kind == 0 ? camera.image({300.0, 60.0, -45.0}, 0.5, rng) : std::vector<float>(n);
        if (frame_kind == 1)
            for (float& v : frame) v = static_cast<float>(counts(rng));
        frame[static_cast<std::size_t>(3 * camera.width + 7)] =
            std::numeric_limits<float>::quiet_NaN();
        const Image reduced = MicrogridPixelReducer(cal).reduce(frame);
        double scale = 0.0;
        for (float v : frame)
            if (std::isfinite(v)) scale = std::max(scale, std::abs(static_cast<double>(v)));
        int singular = 0;
        for (int cy = 0; cy < camera.height / 2; ++cy)
            for (int cx = 0; cx < camera.width / 2; ++cx) {
                const std::size_t o = reduced.index(cx, cy);
                if (cx == 2 && cy == 5) {
                    for (const char* name : {"S0", "S1", "S2", "DoLP", "AoP"})
                        EXPECT_TRUE(std::isnan(reduced.channel(name)[o])) << name;
                    ++singular;
                    continue;
                }
                const auto s = solve_cell_directly(frame, cal, cx, cy);
                for (std::size_t r = 0; r < 3; ++r)
                    ASSERT_NEAR(reduced.channel("S" + std::to_string(r))[o], s[r], 2e-6 * scale)
                        << "cell " << cx << "," << cy << " S" << r;
                const double pl = std::hypot(s[1], s[2]);
                if (s[0] > 0.0)
                    EXPECT_NEAR(reduced.channel("DoLP")[o], pl / s[0], 1e-5 * scale / s[0]);
                else
                    EXPECT_TRUE(std::isnan(reduced.channel("DoLP")[o]));
            }
        EXPECT_EQ(std::get<int>(reduced.attributes().at("singular_cells")), singular);
        EXPECT_EQ(std::get<int>(reduced.attributes().at("cells_with_bad_pixels")), 2);
        const Image one_shot = reduce_microgrid_per_pixel(frame, cal);
        for (std::size_t o = 0; o < reduced.pixel_count(); ++o)
            for (const char* name : {"S0", "S1", "S2", "DoLP", "AoP"}) {
                const float a = one_shot.channel(name)[o], b = reduced.channel(name)[o];
                EXPECT_TRUE(a == b || (std::isnan(a) && std::isnan(b))) << name << " " << o;
            }
    }
}

struct PullStatistics {
    double mean = 0.0, std = 0.0;
    std::size_t count = 0;
};

PullStatistics statistics(const std::vector<double>& pulls) {
    PullStatistics p;
    p.count = pulls.size();
    for (double v : pulls) p.mean += v;
    p.mean /= static_cast<double>(p.count);
    for (double v : pulls) p.std += (v - p.mean) * (v - p.mean);
    p.std = std::sqrt(p.std / static_cast<double>(p.count - 1));
    return p;
}

/// Over 60 seeds of the flat-field noise (a new calibration each) and of the scene frame's noise:
/// (estimate − truth)/σ for S0, S1, S2 and DoLP of every super-pixel. The frame's σ is given to the
/// reduction when it is not 0.
std::array<PullStatistics, 4> pulls_over_seeds(double frame_noise, double flat_field_noise) {
    const MicrogridPattern sony = MicrogridPattern::sony_imx250mzr();
    const PlantedCamera camera(sony, 31);
    const Eigen::Vector3d truth(300.0, 60.0, -45.0);
    const double truth_dolp = std::hypot(truth(1), truth(2)) / truth(0);
    std::array<std::vector<double>, 4> pulls;
    for (std::uint32_t seed = 0; seed < 60; ++seed) {
        std::mt19937 rng(1000 + seed);
        const MicrogridPixelCalibration cal = calibrate_microgrid_pixels(
            flat_fields(camera, flat_field_noise, rng), camera.width, camera.height);
        const std::vector<float> frame = camera.image(truth, frame_noise, rng);
        const std::vector<float> frame_std(frame.size(), static_cast<float>(frame_noise));
        const Image stokes = MicrogridPixelReducer(cal).reduce(
            frame,
            frame_noise > 0.0 ? std::span<const float>(frame_std) : std::span<const float>());
        for (std::size_t o = 0; o < stokes.pixel_count(); ++o) {
            for (std::size_t r = 0; r < 3; ++r) {
                const std::string name = "S" + std::to_string(r);
                pulls[r].push_back((stokes.channel(name)[o] - truth(static_cast<Eigen::Index>(r))) /
                                   stokes.channel(name + "_std")[o]);
            }
            pulls[3].push_back((stokes.channel("DoLP")[o] - truth_dolp) /
                               stokes.channel("DoLP_std")[o]);
        }
    }
    return {statistics(pulls[0]), statistics(pulls[1]), statistics(pulls[2]), statistics(pulls[3])};
}

TEST(MicrogridPixelCalibration, PropagatedSigmaMatchesTheScatterOverSeeds) {
    // The planted camera calibrated from noisy flat fields (σ = 0.5 counts, 16 sources, 12 degrees
    // of freedom per pixel), then a uniform DoLP 0.25 scene: the σ predicted from the fit's
    // residuals (and the frame's σ) must describe the actual error, pulls ~ N(0, 1). Three cases:
    // the calibration's error alone (a noise-free frame), the frame's noise alone (noise-free flat
    // fields), both.
    struct Case {
        const char* what;
        double frame_noise;
        double flat_field_noise;
    };
    for (const Case& c : {Case{"calibration only", 0.0, 0.5}, Case{"frame only", 0.8, 0.0},
                          Case{"both", 0.8, 0.5}}) {
        const auto p = pulls_over_seeds(c.frame_noise, c.flat_field_noise);
        const char* names[] = {"S0", "S1", "S2", "DoLP"};
        for (std::size_t k = 0; k < 4; ++k) {
            std::printf("%s, %s: pull mean %+.3f, std %.3f over %zu\n", c.what, names[k], p[k].mean,
                        p[k].std, p[k].count);
            EXPECT_LT(std::abs(p[k].mean), 0.1) << c.what << " " << names[k];
            EXPECT_GT(p[k].std, 0.9) << c.what << " " << names[k];
            EXPECT_LT(p[k].std, 1.1) << c.what << " " << names[k];
        }
    }
}

TEST(MicrogridPixelCalibration, UncertaintiesRoundTripThroughTheImage) {
    const MicrogridPattern sony = MicrogridPattern::sony_imx250mzr();
    const PlantedCamera camera(sony, 41);
    std::mt19937 rng(42);
    const MicrogridPixelCalibration cal =
        calibrate_microgrid_pixels(flat_fields(camera, 0.5, rng), camera.width, camera.height);
    ASSERT_TRUE(cal.has_uncertainties());
    ASSERT_EQ(cal.unit_parameter_covariance.size(), 16u);
    const Image image = cal.to_image();
    // w0_std = residual σ · √((AᵀA)⁻¹)₀₀: the standard uncertainty of the fitted w0.
    EXPECT_FLOAT_EQ(
        image.channel("w0_std")[5],
        cal.residual_std[5] * static_cast<float>(std::sqrt(cal.unit_parameter_covariance[0])));
    const MicrogridPixelCalibration back = MicrogridPixelCalibration::from_image(image);
    EXPECT_EQ(back.residual_std, cal.residual_std);
    EXPECT_EQ(back.unit_parameter_covariance, cal.unit_parameter_covariance);
    const std::vector<float> frame = camera.image({300.0, 60.0, -45.0}, 0.0, rng);
    EXPECT_EQ(MicrogridPixelReducer(back).reduce(frame).channel("S1_std"),
              MicrogridPixelReducer(cal).reduce(frame).channel("S1_std"));
    // Without the covariance the σ channel cannot be used: refused, naming the attribute.
    Image broken = image;
    broken.attributes().erase("unit_parameter_covariance");
    EXPECT_THROW(MicrogridPixelCalibration::from_image(broken), Error);
    // Too few sources for a residual (4 sources, 4 parameters): no uncertainties, no σ channels.
    std::vector<MicrogridFlatField> four(flat_fields(camera, 0.0, rng));
    four = {four[0], four[1], four[2], four[9]};
    const MicrogridPixelCalibration exact =
        calibrate_microgrid_pixels(four, camera.width, camera.height);
    EXPECT_FALSE(exact.has_uncertainties());
    EXPECT_FALSE(MicrogridPixelReducer(exact).reduce(frame).has_channel("S0_std"));
}

TEST(MicrogridPixelCalibration, RefusesSourcesThatCannotSeparateTheModel) {
    const MicrogridPattern sony = MicrogridPattern::sony_imx250mzr();
    const PlantedCamera camera(sony, 3);
    std::mt19937 rng(3);
    std::vector<MicrogridFlatField> one_radiance = flat_fields(camera, 0.0, rng);
    one_radiance.resize(8);  // the polarizer at one radiance: S0 cannot be told from the background
    try {
        calibrate_microgrid_pixels(one_radiance, camera.width, camera.height);
        FAIL() << "a rank-deficient calibration was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("two source radiances"), std::string::npos)
            << e.what();
    }
    EXPECT_NO_THROW(calibrate_microgrid_pixels(one_radiance, camera.width, camera.height, false));
    EXPECT_THROW(calibrate_microgrid_pixels(one_radiance, camera.width + 2, camera.height), Error);
    const MicrogridPixelCalibration cal =
        calibrate_microgrid_pixels(one_radiance, camera.width, camera.height, false);
    EXPECT_THROW(reduce_microgrid_per_pixel(std::vector<float>(8, 1.0f), cal), Error);
}

}  // namespace
}  // namespace tirpol::calibration
