// `tirpol noise`'s library side from files: a directory of frames of pure white temporal noise
// splits the noise drawn over the 3D-noise components, with a report file that says so; the
// summary text names it.

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>

#include "test_support.h"
#include "tirpol/calibration/noise.h"
#include "tirpol/core/exr_io.h"

namespace tirpol::calibration {
namespace {

using ::testing::HasSubstr;

TEST(NoiseRun, WhiteNoiseStackFromFilesGivesItsSigmaInReportAndText) {
    const test::TempDir dir("noise_run");
    std::filesystem::create_directories(dir / "stack");
    std::mt19937 rng(7);
    std::normal_distribution<float> noise(1000.0f, 2.0f);
    constexpr int kSide = 32, kFrames = 16;
    for (int f = 0; f < kFrames; ++f) {
        Image frame(kSide, kSide);
        auto& c = frame.add_channel("counts");
        for (auto& v : c) v = noise(rng);
        write_exr(dir / "stack" / fmt::format("frame_{:02d}.exr", f), frame);
    }
    NoiseRunOptions o;
    o.stack = (dir / "stack").string();
    o.output = (dir / "noise.json").string();
    o.nedt_map = (dir / "nedt.exr").string();  // needs a calibration: not written without one
    const NoiseAnalysis a = run_noise_analysis(o);
    EXPECT_EQ(a.frames, static_cast<std::size_t>(kFrames));
    // White noise splits over the seven components; together they hold all of it.
    const auto& d = a.three_d_noise_counts;
    EXPECT_NEAR(std::sqrt(d.sigma_tvh * d.sigma_tvh + d.sigma_vh * d.sigma_vh +
                          d.sigma_v * d.sigma_v + d.sigma_h * d.sigma_h + d.sigma_t * d.sigma_t +
                          d.sigma_tv * d.sigma_tv + d.sigma_th * d.sigma_th),
                2.0, 0.1);
    EXPECT_GT(d.sigma_tvh, d.sigma_v);
    EXPECT_NEAR(a.temporal_noise_median_counts, 2.0, 0.15);
    EXPECT_FALSE(a.kelvin);
    EXPECT_FALSE(std::filesystem::exists(o.nedt_map));
    std::ifstream in(o.output);
    const nlohmann::json report = nlohmann::json::parse(in);
    EXPECT_EQ(report["frames"], kFrames);
    EXPECT_EQ(report["stack"], o.stack);
    const std::string text = noise_analysis_text(a, o.output);
    EXPECT_THAT(text, HasSubstr("16 frames; 3D noise (counts, sample"));
    EXPECT_THAT(text, HasSubstr("→ " + o.output + "\n"));
    EXPECT_THAT(text, ::testing::Not(HasSubstr("NEDT")));
}

}  // namespace
}  // namespace tirpol::calibration
