// A sensor-NEDT axis: each point's polarizer images come from the sensor model with that NEDT, so
// their temporal noise in counts, σ = gain·NEDT·dL/dT(T_ref) (sensor_model.h), scales with the
// NEDT.

#include <gtest/gtest.h>

#include <cmath>

#include "sweep_test_support.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/sweep/sweep_run.h"

namespace tirpol::sweep {
namespace {

/// Standard deviation of counts − (gain·radiance + offset): the noise the sensor model added.
double counts_noise_std(const std::filesystem::path& pol_exr, double gain, double offset) {
    const Image image = read_exr(pol_exr);
    const auto &counts = image.channel("counts"), &radiance = image.channel("radiance");
    double sum = 0.0, sum2 = 0.0;
    for (std::size_t i = 0; i < counts.size(); ++i) {
        const double noise = counts[i] - (gain * radiance[i] + offset);
        sum += noise;
        sum2 += noise * noise;
    }
    const double n = static_cast<double>(counts.size());
    return std::sqrt(sum2 / n - (sum / n) * (sum / n));
}

TEST(SweepSensor, PolarizerImageNoiseFollowsTheSweptNedt) {
    tirpol::test::TempDir dir;
    tirpol::test::write_text(
        dir / "sensor.yaml",
        "counts: {gain_counts_per_radiance: 200, offset_counts: 1000, nedt_k: 0.5}\n");
    const auto spec = load_sweep(test::write_small_sweep(
        dir, "sensor: sensor.yaml\naxes:\n  sensor.counts.nedt_k: [0.5, 2.0]\n"));
    const auto summary = run_sweep(spec, dir / "out", {1, false, false});
    ASSERT_EQ(summary.rendered, 2u);
    for (const char* angle : {"000", "045", "090", "135"})
        EXPECT_TRUE(std::filesystem::is_regular_file(dir / "out/points/p0000" /
                                                     (std::string("pol") + angle + ".exr")));
    const double low = counts_noise_std(dir / "out/points/p0000/pol000.exr", 200, 1000);
    const double high = counts_noise_std(dir / "out/points/p0001/pol000.exr", 200, 1000);
    ASSERT_GT(low, 0.0);
    // 768 pixels: each standard deviation is known to ≈ 1/√(2·768) = 2.6 %, the ratio to ≈ 4 %.
    EXPECT_NEAR(high / low, 4.0, 0.5);
}

}  // namespace
}  // namespace tirpol::sweep
