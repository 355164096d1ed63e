// Requires TIRPOL_WITH_ARAVIS (built only with that back end: cmake/TirpolBackends.cmake).
// The microgrid (DoFP) camera's twin end to end on the simulated camera: panels_night rendered at
// the sensor's full resolution, seen through a DoFP sensor with a planted manufacturing spread,
// served free-running over GigE Vision in PolarizeMono16; the flat-field rig recorded through the
// simulated stage; `calibrate_microgrid_sessions`; the scene captured and reduced per super-pixel.
// The scene's Stokes per region must come back within noise (pulls ~ N(0, 1)) and the planted
// per-pixel analyzers must be recovered far below their spread.

#include <gtest/gtest.h>

#include <cstdio>

#include "test_support.h"
#include "tirpol/twin/dofp_twin.h"

namespace tirpol::twin {
namespace {

/// The test's camera: a 10 % array (Powell & Gruev: up to 20 %): axis σ 2°, d 0.92 ± 0.03, t and R
/// ± 10 %.
DofpTwinOptions test_options(const test::TempDir& dir) {
    DofpTwinOptions options;
    options.out_dir = dir.path() / "dofp";
    options.scene_file = test::source_dir() / "config/scenes/panels_night.yaml";
    options.genicam_xml = test::source_dir() / "tests/data/genicam/polarized-fake-camera.xml";
    options.width = 128;
    options.height = 96;
    options.spp = 4;
    options.threads = 2;
    options.sensor.spread.axis_sigma_deg = 2.0;
    options.sensor.spread.diattenuation_mean = 0.92;
    options.sensor.spread.diattenuation_sigma = 0.03;
    options.sensor.spread.transmission_rel_sigma = 0.1;
    options.sensor.spread.responsivity_rel_sigma = 0.1;
    options.sensor.seed = 28;
    return options;
}

void expect_recovered(const DofpTwinResult& r) {
    // Planted per-pixel parameters recovered far below their spread: temporal noise over 16
    // frames per record leaves ~0.005° and ~5e-4 in d (docs/twin.md gives the run's figures).
    const DofpParameterRecovery& p = r.parameters;
    EXPECT_EQ(r.bad_pixels, 0u) << "no bad pixel was planted";
    EXPECT_GT(p.planted_axis_spread_deg, 1.5);
    EXPECT_LT(p.axis_rms_deg, 0.1 * p.planted_axis_spread_deg);
    EXPECT_LT(p.diattenuation_rms, 0.1 * p.planted_diattenuation_spread);
    EXPECT_LT(p.gain_rel_rms, 0.1 * p.planted_gain_rel_spread);

    // The scene's Stokes per region within noise: pulls (measured − truth)/σ ~ N(0, 1). Over 30
    // values the RMS of N(0, 1) pulls lies in [0.6, 1.4] with > 99 % probability (the scatter σ of
    // 16–27 cells adds Student-t tails); a bias of a few σ (a wrong pattern, sign or analyzer)
    // gives pulls of tens.
    ASSERT_GE(r.regions.size(), 5u);
    EXPECT_LT(r.pull_rms, 1.6);
    EXPECT_GT(r.pull_rms, 0.4) << "σ too large to test anything";
    EXPECT_LT(r.pull_max_abs, 4.5);
    // Ideal analyzers at the nominal pattern (the NUC alone) leave biases the pulls see.
    EXPECT_GT(r.pull_rms_nuc_only, 2.0 * r.pull_rms);
}

TEST(DofpTwin, RecoversSceneStokesWithinNoiseAndThePlantedAnalyzers) {
    test::TempDir dir;
    const DofpTwinResult r = run_dofp_twin(test_options(dir));
    std::printf("%s", dofp_twin_summary(r).c_str());

    // The camera really was the free-running GigE Vision microgrid camera (no silent fallback).
    EXPECT_EQ(r.camera_transport.rfind("GigE Vision", 0), 0u) << r.camera_transport;
    EXPECT_EQ(r.pixel_format, "PolarizeMono16");
    EXPECT_GT(r.frame_rate_hz, 20.0);

    expect_recovered(r);
}

TEST(DofpTwin, InProcessMicrogridCameraGivesTheSameChain) {
    // Without GigE Vision the twin serves the DoFP sensor through the in-process SimulatedCamera,
    // now a microgrid camera itself (pattern in CameraInfo, PolarizeMono16), free-running at 60 Hz.
    test::TempDir dir;
    DofpTwinOptions options = test_options(dir);
    options.gige = false;
    const DofpTwinResult r = run_dofp_twin(options);
    std::printf("%s", dofp_twin_summary(r).c_str());
    EXPECT_EQ(r.camera_transport.rfind("in-process SimulatedCamera", 0), 0u) << r.camera_transport;
    EXPECT_EQ(r.pixel_format, "PolarizeMono16");
    EXPECT_GT(r.frame_rate_hz, 20.0);
    expect_recovered(r);
}

}  // namespace
}  // namespace tirpol::twin
