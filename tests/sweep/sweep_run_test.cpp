// Running a sweep on one machine: atomic point folders, manifest, failing points, resume, and the
// Monte-Carlo errors of the region statistics.

#include "tirpol/sweep/sweep_run.h"

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "sweep_test_support.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/error.h"

namespace tirpol::sweep {
namespace {

using tirpol::test::TempDir;

nlohmann::json manifest_of(const std::filesystem::path& out) {
    return nlohmann::json::parse(read_file(out / "manifest.json"));
}

TEST(SweepRun, FailingPointIsRecordedAndTheSweepGoesOn) {
    TempDir dir;
    // The second band is reversed: the scene loader refuses it, the first point still renders.
    const auto spec = load_sweep(test::write_small_sweep(
        dir, "axes:\n  band: [{lo_um: 8, hi_um: 14}, {lo_um: 14, hi_um: 8}]\n"));
    const auto out = dir / "out";
    const SweepSummary summary = run_sweep(spec, out, {1, false, false});
    EXPECT_EQ(summary.rendered, 1u);
    EXPECT_EQ(summary.failed, 1u);
    const auto manifest = manifest_of(out);
    ASSERT_EQ(manifest["points"].size(), 2u);
    EXPECT_EQ(manifest["points"][0]["status"], "rendered");
    EXPECT_EQ(manifest["points"][1]["status"], "failed");
    EXPECT_NE(manifest["points"][1]["error"].get<std::string>().find("hi_um"), std::string::npos);
    EXPECT_EQ(manifest["points"][1]["parameters"]["band"], "{lo_um: 14, hi_um: 8}");
    EXPECT_TRUE(std::filesystem::is_regular_file(out / "points/p0000/stokes.exr"));
    EXPECT_FALSE(std::filesystem::exists(out / "points/p0001"));
    for (const auto& entry : std::filesystem::directory_iterator(out / "points"))
        EXPECT_EQ(entry.path().filename().string().find(".partial"), std::string::npos)
            << "left behind: " << entry.path();
    const std::string csv = read_file(out / "results.csv");
    EXPECT_NE(csv.find("\n1,p0001,failed,\"{lo_um: 14, hi_um: 8}\""), std::string::npos) << csv;
}

TEST(SweepRun, ResumeRendersOnlyUnfinishedPointsIdentically) {
    TempDir dir;
    const auto spec =
        load_sweep(test::write_small_sweep(dir, "axes:\n  camera.fov_deg: [18, 22, 26]\n"));
    const auto out = dir / "out";
    ASSERT_EQ(run_sweep(spec, out, {1, false, false}).rendered, 3u);
    const std::string first = read_file(out / "points/p0001/stokes.exr");
    std::filesystem::remove_all(out /
                                "points/p0001");  // as if interrupted before this point finished

    try {
        run_sweep(spec, out, {1, false, false});
        ADD_FAILURE() << "a second run into the same folder without --resume must be refused";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("--resume"), std::string::npos) << e.what();
    }
    const SweepSummary resumed = run_sweep(spec, out, {2, true, false});
    EXPECT_EQ(resumed.rendered, 1u);
    EXPECT_EQ(resumed.resumed, 2u);
    EXPECT_EQ(read_file(out / "points/p0001/stokes.exr"), first)
        << "same seed, same image, whatever the thread count";
    ASSERT_TRUE(resumed.points[0].statistics.has_value());

    const auto other = load_sweep(
        test::write_small_sweep(dir, "axes:\n  camera.fov_deg: [18, 23, 26]\n", "other.yaml"));
    try {
        run_sweep(other, out, {1, true, false});
        ADD_FAILURE() << "resuming a different sweep into the folder must be refused";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("different sweep"), std::string::npos) << e.what();
    }
}

// The Monte-Carlo error of each region mean (√Σvar/n) must explain the difference between two
// seeds: z = (m₁ − m₂)/√(σ₁² + σ₂²) ~ N(0, 1), so |z| < 5 unless the errors are underestimated.
TEST(SweepRun, MonteCarloErrorsExplainSeedToSeedDifferences) {
    TempDir dir;
    const std::string body =
        "axes:\n  sampling.spp: [8]\ncontrasts:\n  ball_vs_snow: {a: ball, b: snow}\n";
    const auto a = run_sweep(load_sweep(test::write_small_sweep(dir, "seed: 1\n" + body, "a.yaml")),
                             dir / "a", {1, false, false});
    const auto b = run_sweep(load_sweep(test::write_small_sweep(dir, "seed: 2\n" + body, "b.yaml")),
                             dir / "b", {1, false, false});
    const auto& sa = *a.points[0].statistics;
    const auto& sb = *b.points[0].statistics;
    ASSERT_EQ(sa.regions.size(), 3u);  // one region per object by default: snow, ball, panel
    int compared = 0;
    double sum_z2 = 0.0;
    for (std::size_t r = 0; r < sa.regions.size(); ++r) {
        EXPECT_GT(sa.regions[r].pixel_count, 0u) << sa.regions[r].name;
        for (std::size_t q = 0; q < 3; ++q) {
            const Estimate &ea = quantity(sa.regions[r].values, q),
                           &eb = quantity(sb.regions[r].values, q);
            ASSERT_GT(ea.error, 0.0) << sa.regions[r].name << " " << kQuantityNames[q];
            const double z = (ea.mean - eb.mean) / std::hypot(ea.error, eb.error);
            EXPECT_LT(std::abs(z), 5.0) << sa.regions[r].name << " " << kQuantityNames[q];
            sum_z2 += z * z;
            ++compared;
        }
    }
    EXPECT_GT(sum_z2, 0.0) << "different seeds must give different images";
    const Estimate& contrast = sa.contrasts[0].values.s0;
    EXPECT_NEAR(contrast.mean, sa.regions[1].values.s0.mean - sa.regions[0].values.s0.mean, 1e-12);
    EXPECT_NEAR(contrast.error,
                std::hypot(sa.regions[1].values.s0.error, sa.regions[0].values.s0.error), 1e-15);
    EXPECT_EQ(compared, 9);
}

}  // namespace
}  // namespace tirpol::sweep
