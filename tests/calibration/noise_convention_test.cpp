// `tirpol noise` as others compute it: 3D-noise components with the sample
// (N − 1) normalisation of pyradi's ry3dnoise (NelisW/pyradi, pyradi/ry3dnoise.py: every component
// is np.std(..., ddof=1)) against hand-computed cubes; stacks from PNG/TIFF folders and raw files;
// noise in kelvin after the calibration, where the fixed pattern the calibration removes is gone.

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <random>

#include "synthetic_fpa_camera.h"
#include "test_support.h"
#include "tirpol/calibration/noise.h"
#include "tirpol/core/error.h"

namespace tirpol::calibration {
namespace {

FrameStack cube(int nt, int nv, int nh, const std::function<double(int, int, int)>& u) {
    FrameStack s;
    s.width = nh;
    s.height = nv;
    for (int t = 0; t < nt; ++t) {
        std::vector<float> f;
        for (int v = 0; v < nv; ++v)
            for (int h = 0; h < nh; ++h) f.push_back(static_cast<float>(u(t, v, h)));
        s.frames.push_back(f);
    }
    return s;
}

TEST(NoiseConvention, HandComputedFrameFlickerAndRowNoise) {
    // Two 2×2 frames at 1 and 3 counts: S = 2, N_t = (−1, +1), nothing else. Population σ_t =
    // √(2/2) = 1; sample σ_t = √(2/1) = √2.
    const auto flicker = cube(2, 2, 2, [](int t, int, int) { return t == 0 ? 1.0 : 3.0; });
    EXPECT_DOUBLE_EQ(three_d_noise(flicker, NoiseConvention::Population).sigma_t, 1.0);
    EXPECT_DOUBLE_EQ(three_d_noise(flicker, NoiseConvention::Sample).sigma_t, std::sqrt(2.0));
    EXPECT_DOUBLE_EQ(three_d_noise(flicker, NoiseConvention::Sample).sigma_vh, 0.0);
    // Rows at 0 and 4 in both frames: N_v = (−2, +2); population 2, sample √(8/1).
    const auto rows = cube(2, 2, 3, [](int, int v, int) { return v == 0 ? 0.0 : 4.0; });
    EXPECT_DOUBLE_EQ(three_d_noise(rows, NoiseConvention::Population).sigma_v, 2.0);
    EXPECT_DOUBLE_EQ(three_d_noise(rows, NoiseConvention::Sample).sigma_v, std::sqrt(8.0));
    EXPECT_DOUBLE_EQ(three_d_noise(rows, NoiseConvention::Sample).sigma_t, 0.0);
}

TEST(NoiseConvention, SampleIsPopulationTimesRootNOverNMinusOneForEachComponent) {
    // The case: 20 frames of 100×100 — σ_t 2.5 % and σ_v, σ_h 0.5 % above the population
    // values.
    std::mt19937 rng(3);
    std::normal_distribution<double> unit(0.0, 1.0);
    const auto s = cube(20, 100, 100, [&](int, int, int) { return 1000.0 + 5.0 * unit(rng); });
    const auto pop = three_d_noise(s, NoiseConvention::Population);
    const auto smp = three_d_noise(s, NoiseConvention::Sample);
    EXPECT_NEAR(smp.sigma_t / pop.sigma_t, std::sqrt(20.0 / 19.0), 1e-12);
    EXPECT_NEAR(smp.sigma_v / pop.sigma_v, std::sqrt(100.0 / 99.0), 1e-12);
    EXPECT_NEAR(smp.sigma_h / pop.sigma_h, std::sqrt(100.0 / 99.0), 1e-12);
    EXPECT_NEAR(smp.sigma_tv / pop.sigma_tv, std::sqrt(2000.0 / 1999.0), 1e-12);
    EXPECT_NEAR(smp.sigma_vh / pop.sigma_vh, std::sqrt(10000.0 / 9999.0), 1e-12);
    EXPECT_NEAR(smp.sigma_tvh / pop.sigma_tvh, std::sqrt(200000.0 / 199999.0), 1e-12);
    EXPECT_STREQ(to_string(NoiseConvention::Sample), "sample (N-1, as pyradi ry3dnoise)");
}

TEST(FrameStackIo, ReadsPngAndTiffFoldersAndRawFiles) {
    test::TempDir dir;
    std::filesystem::create_directories(dir / "png");
    std::filesystem::create_directories(dir / "tif");
    std::ofstream raw(dir / "stack.raw", std::ios::binary);
    raw.write("HDR!", 4);  // a 4-byte header to skip
    for (int t = 0; t < 3; ++t) {
        cv::Mat m(3, 4, CV_16UC1);
        for (int y = 0; y < 3; ++y)
            for (int x = 0; x < 4; ++x) {
                const std::uint16_t v = static_cast<std::uint16_t>(1000 * t + 10 * y + x + 40000);
                m.at<std::uint16_t>(y, x) = v;
                const char bytes[2] = {static_cast<char>(v & 0xff), static_cast<char>(v >> 8)};
                raw.write(bytes, 2);
            }
        ASSERT_TRUE(cv::imwrite((dir / "png" / fmt::format("f{:02d}.png", t)).string(), m));
        ASSERT_TRUE(cv::imwrite((dir / "tif" / fmt::format("f{:02d}.tif", t)).string(), m));
    }
    raw.close();
    for (const auto& stack :
         {load_frame_stack(dir / "png"), load_frame_stack(dir / "tif"),
          load_frame_stack(dir / "stack.raw",
                           RawFrameFormat{4, 3, RawFrameFormat::Type::UInt16, 4})}) {
        ASSERT_EQ(stack.frames.size(), 3u);
        EXPECT_EQ(stack.width, 4);
        EXPECT_EQ(stack.height, 3);
        EXPECT_EQ(stack.frames[2][1 * 4 + 3], 42013.0f);  // frame 2, y = 1, x = 3
    }
    EXPECT_THAT(
        [&] {
            load_frame_stack(dir / "stack.raw",
                             RawFrameFormat{5, 3, RawFrameFormat::Type::UInt16, 4});
        },
        testing::ThrowsMessage<Error>(
            testing::HasSubstr("not 4 header bytes + a whole number of 5×3 frames")));
    std::filesystem::create_directories(dir / "empty");
    EXPECT_THAT([&] { load_frame_stack(dir / "empty"); },
                testing::ThrowsMessage<Error>(
                    testing::HasSubstr("no frame files (.exr, .png, .tif, .tiff)")));
}

TEST(FrameStackIo, NoiseInKelvinAfterCalibrationHasNoFixedPattern) {
    // 150 counts of offset non-uniformity ≈ 2 K of fixed pattern in counts; after the calibration
    // the spatial component is the calibration's own error (≈ σ/√16 per pixel over 6 set-points, ≈
    // 10 mK).
    DriftingCamera cam;
    const DriftingCameraTruth truth(cam);
    const Band band(8.0, 14.0);
    std::vector<BlackbodyFrame> frames;
    for (double t : {283.15, 293.15, 303.15, 313.15, 323.15, 333.15})
        frames.push_back(truth.frame(band, t, 303.15, 7u + static_cast<unsigned>(t)));
    const auto cal = fit_radiometric(frames, cam.width, cam.height, band);
    DriftingCamera single = cam;
    single.frames = 1;  // raw frames: σ = 4 counts each
    const DriftingCameraTruth raw(single);
    FrameStack stack{cam.width, cam.height, {}};
    for (unsigned t = 0; t < 20; ++t)
        stack.frames.push_back(raw.frame(band, 300.0, 303.15, 500 + t).counts);
    const auto counts = three_d_noise(stack, NoiseConvention::Sample);
    const auto kelvin = three_d_noise(temperature_stack(stack, cal), NoiseConvention::Sample);
    const double responsivity = cam.gain_mean * band.radiance_dT(300.0);  // counts/K
    EXPECT_GT(counts.sigma_vh / responsivity, 1.0);
    EXPECT_LT(kelvin.sigma_vh, 0.025);
    EXPECT_NEAR(kelvin.mean, 300.0, 0.02);
    // Random noise: 4 counts ≈ 53 mK per frame.
    EXPECT_NEAR(kelvin.sigma_tvh, cam.noise_counts / responsivity,
                0.15 * cam.noise_counts / responsivity);
}

}  // namespace
}  // namespace tirpol::calibration
