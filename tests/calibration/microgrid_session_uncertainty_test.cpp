// The σ a calibrated microgrid session's reduction states (S0_std … DoLP_std) against the scatter
// of repeated calibrations and captures of one simulated camera with known temporal noise: each
// repeat draws new noise for the flat-field sessions (so a new per-pixel calibration) and for the
// scene, as a second day in the laboratory would. The stated σ must match the scatter, and must
// need both parts (the frame's temporal σ and the calibration's parameter covariance).

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "test_support.h"
#include "tirpol/calibration/microgrid_session.h"
#include "tirpol/calibration/synthetic_session.h"
#include "tirpol/core/error.h"

namespace tirpol::calibration {
namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;
constexpr const char* kChannels[4] = {"S0", "S1", "S2", "DoLP"};

struct Repeat {
    Image stokes, stokes_frame_noise_only;
    std::vector<float> bad;
};

Repeat calibrate_and_reduce(const SyntheticMicrogridCamera& camera, const Band& band,
                            const Eigen::Vector3d& scene) {
    test::TempDir dir;
    write_synthetic_microgrid_flat_field(dir / "flat", camera, band);
    MicrogridFlatFieldCalibration calibration = calibrate_microgrid_sessions({dir / "flat"}, band);
    write_synthetic_microgrid_scene(dir / "scene", camera, uniform_stokes_scene(camera, scene));
    Repeat r;
    MicrogridSessionOptions options;
    options.pixel_calibration = calibration.pixels;
    r.stokes = reduce_microgrid_session(dir / "scene", options);
    for (auto& plane : options.pixel_calibration->parameter_covariance) plane.clear();
    r.stokes_frame_noise_only = reduce_microgrid_session(dir / "scene", options);
    r.bad = calibration.pixels.bad;
    return r;
}

TEST(MicrogridSessionUncertainty, StatedSigmaMatchesScatterOverRepeatedCalibrationsAndCaptures) {
    const Band band(8.0, 14.0);
    SyntheticMicrogridCamera camera;
    camera.width = 24;
    camera.height = 16;
    camera.analyzer_spread = 0.1;
    camera.noise_counts = 20.0;
    camera.frames = 8;
    camera.dead_x = 3;
    camera.dead_y = 3;
    camera.hot_x = 10;
    camera.hot_y = 7;
    camera.noisy_x = 17;
    camera.noisy_y = 12;
    const double s0 = band.radiance(300.0), dolp = 0.3;
    const Eigen::Vector3d scene(s0, s0 * dolp * std::cos(60.0 * kDegToRad),
                                s0 * dolp * std::sin(60.0 * kDegToRad));
    constexpr int kRepeats = 24;
    std::vector<Repeat> repeats;
    for (int r = 0; r < kRepeats; ++r) {
        camera.capture_seed = static_cast<unsigned>(r + 1);
        repeats.push_back(calibrate_and_reduce(camera, band, scene));
    }
    const Image& first = repeats.front().stokes;
    ASSERT_TRUE(first.has_channel("DoLP_std"));
    EXPECT_EQ(std::get<std::string>(first.attributes().at("std_includes")),
              "the frame's σ and the per-pixel calibration's fit error");
    // Cells with a pixel found bad in any repeat are reduced from a varying set of pixels: out.
    const auto cells = first.pixel_count();
    const auto half_width = static_cast<std::size_t>(first.width());
    std::vector<bool> use(cells, true);
    for (const Repeat& r : repeats)
        for (std::size_t i = 0; i < r.bad.size(); ++i)
            if (r.bad[i] != 0.0f) {
                const std::size_t x = i % static_cast<std::size_t>(camera.width),
                                  y = i / static_cast<std::size_t>(camera.width);
                use[(y / 2) * half_width + x / 2] = false;
            }
    std::size_t used = 0;
    for (bool u : use) used += u ? 1 : 0;
    ASSERT_GT(used, cells / 2);

    // Per channel: Σ over cells of the sample variance over repeats / Σ of the mean stated
    // variance. Each cell's sample variance has relative σ √(2/(R−1)); over K independent cells
    // the ratio's relative σ is √(2/(K(R−1))).
    const double sampling_error =
        std::sqrt(2.0 / (static_cast<double>(used) * static_cast<double>(kRepeats - 1)));
    for (const char* channel : kChannels) {
        const std::string std_channel = std::string(channel) + "_std";
        double scatter = 0.0, stated = 0.0, frame_only = 0.0;
        for (std::size_t cell = 0; cell < cells; ++cell) {
            if (!use[cell]) continue;
            double mean = 0.0;
            for (const Repeat& r : repeats) mean += r.stokes.channel(channel)[cell];
            mean /= kRepeats;
            double sum_sq = 0.0, stated_var = 0.0, frame_var = 0.0;
            for (const Repeat& r : repeats) {
                const double e = r.stokes.channel(channel)[cell] - mean;
                sum_sq += e * e;
                const double sigma = r.stokes.channel(std_channel)[cell];
                const double sigma_frame = r.stokes_frame_noise_only.channel(std_channel)[cell];
                stated_var += sigma * sigma;
                frame_var += sigma_frame * sigma_frame;
            }
            scatter += sum_sq / (kRepeats - 1);
            stated += stated_var / kRepeats;
            frame_only += frame_var / kRepeats;
        }
        const double ratio = scatter / stated, frame_ratio = scatter / frame_only;
        std::printf(
            "%s: scatter variance / stated variance %.3f (sampling error %.3f); / frame-noise-only "
            "variance %.3f\n",
            channel, ratio, sampling_error, frame_ratio);
        EXPECT_NEAR(ratio, 1.0, 4.0 * sampling_error) << channel;
        // Without the calibration's covariance the stated σ is too small: the calibration's
        // error is a visible part of the scatter.
        EXPECT_GT(frame_ratio, 1.0 + 6.0 * sampling_error) << channel;
    }
}

TEST(MicrogridSessionUncertainty, PerPixelCovarianceRoundTripsThroughItsImage) {
    const Band band(8.0, 14.0);
    SyntheticMicrogridCamera camera;
    camera.width = 8;
    camera.height = 8;
    camera.dead_x = camera.dead_y = camera.hot_x = camera.noisy_x = 1;
    camera.hot_y = 2;
    camera.noisy_y = 3;
    test::TempDir dir;
    write_synthetic_microgrid_flat_field(dir / "flat", camera, band);
    const MicrogridPixelCalibration cal = calibrate_microgrid_sessions({dir / "flat"}, band).pixels;
    ASSERT_TRUE(cal.has_pixel_covariance());
    const Image image = cal.to_image();
    // A variance is positive; the stated σ is the covariance's diagonal.
    for (std::size_t i = 0; i < image.pixel_count(); ++i) {
        ASSERT_GT(cal.parameter_covariance[0][i], 0.0f);
        ASSERT_GT(cal.parameter_covariance[9][i], 0.0f);
        ASSERT_FLOAT_EQ(image.channel("background_std")[i],
                        std::sqrt(cal.parameter_covariance[9][i]));
    }
    const MicrogridPixelCalibration back = MicrogridPixelCalibration::from_image(image);
    EXPECT_EQ(back.parameter_covariance, cal.parameter_covariance);
    Image missing(image.width(), image.height());
    for (const std::string& name : image.channel_names())
        if (name != "cov_w1_b") missing.set_channel(name, image.channel(name));
    EXPECT_THROW(MicrogridPixelCalibration::from_image(missing), Error);
}

}  // namespace
}  // namespace tirpol::calibration
