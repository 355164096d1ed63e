// The twin's camera geometry: the truth camera has a realistic lens and a pose error;
// the field procedure — geometric calibration from heated-checkerboard frames filmed through the
// sensor model (NEDT 50 mK), pose from the surveyed panel corners — must recover fx and fy within
// the 0.5 %, the principal point and the distortion within their reported uncertainty, and
// a pose that puts the scene on the truth's pixel grid, far better than the nominal set-up it
// started from.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "test_support.h"
#include "tirpol/core/camera_model.h"
#include "tirpol/twin/twin.h"

namespace tirpol::twin {
namespace {

TEST(TwinCameraGeometry, TheFieldProcedureRecoversTheLensAndThePose) {
    test::TempDir dir;
    simulation::Scene field =
        simulation::load_scene(test::source_dir() / "config/scenes/panels_night.yaml");
    const simulation::PinholeCamera nominal =
        field.camera.resized(160, 120);  // the demo's resolution
    const simulation::PinholeCamera truth = with_pose_error(with_realistic_lens(nominal));
    const TwinWorld world(twin_sensor(field.band, 279.15), field.band, 160, 120);
    CameraGeometryOptions options;
    options.threads = 2;
    const CameraGeometryRecovery r =
        recover_camera_geometry(field, truth, nominal, world, dir.path(), options);

    // Where the recovered camera puts the panel corners, against the truth (what the comparison
    // needs).
    double worst_px = 0.0;
    for (std::size_t i = 0; i < field.objects.size(); ++i)
        if (field.objects[i].name.rfind("panel_", 0) == 0)
            for (const Vec3& corner : field.tracer->mesh(static_cast<std::uint32_t>(i)).positions)
                worst_px = std::max(worst_px,
                                    (*r.camera().project(corner) - *truth.project(corner)).norm());
    std::printf(
        "lens from %d of %d frames, RMS %.4f px; fx %.3f/%.3f fy %.3f/%.3f cx %.3f/%.3f ± %.3f cy "
        "%.3f/%.3f ± %.3f\n",
        r.lens.views, r.board_frames, r.lens.rms_px, r.lens.fx, r.true_lens.fx, r.lens.fy,
        r.true_lens.fy, r.lens.cx, r.true_lens.cx, r.lens.std_dev[2], r.lens.cy, r.true_lens.cy,
        r.lens.std_dev[3]);
    std::printf(
        "pose from %d points: %.4f° %.4f m (nominal %.3f° %.4f m); panel corners within %.3f px of "
        "the truth\n",
        r.control_points, r.rotation_error_deg, r.position_error_m, r.nominal_rotation_error_deg,
        r.nominal_position_error_m, worst_px);

    EXPECT_GE(r.lens.views, 15) << "most board frames must show the board";
    EXPECT_LT(r.lens.rms_px,
              0.15);  // Monte Carlo edges at 64 spp and 50 mK of sensor noise: < 0.1 px
    // The focal lengths within the 0.5 %.
    EXPECT_NEAR(r.lens.fx, r.true_lens.fx, 0.005 * r.true_lens.fx);
    EXPECT_NEAR(r.lens.fy, r.true_lens.fy, 0.005 * r.true_lens.fy);
    // The principal point, within 3 of its reported σ. On a 160×120 detector with ~0.09 px of
    // corner noise σ is ~1.2 px with the board rolled ±180° between views (3.5 px for cx with
    // ±25°), more than the 0.5 % of cx (0.4 px), which needs a larger detector or many more
    // views (docs/twin.md, "Known limits").
    EXPECT_NEAR(r.lens.cx, r.true_lens.cx, 3.0 * r.lens.std_dev[2]);
    EXPECT_NEAR(r.lens.cy, r.true_lens.cy, 3.0 * r.lens.std_dev[3]);
    EXPECT_LT(r.lens.std_dev[2], 2.0);
    EXPECT_LT(r.lens.std_dev[3], 2.0);
    // The distortion within 3σ, as the principal point. With the renderer's per-pixel strata (lower
    // Monte Carlo noise on the board's edges) p1 comes out ≈ +0.001 from the truth at 2.2–2.7σ for
    // 48–128 board spp (and at 2.2σ with the old sampling at 256 spp): a small systematic offset of
    // the detection or the fit, not found yet, that moves image points by < 0.07 px at the corners
    // — the panel-corner check below bounds what matters.
    for (std::size_t i = 0; i < 4; ++i)  // k3 is held at 0 (--fix-k3), as is the truth's
        EXPECT_LT(std::abs(r.lens.distortion[i] - r.true_lens.distortion[i]),
                  3.0 * r.lens.std_dev[4 + i])
            << r.lens_parameter_names[4 + i] << " " << r.lens.distortion[i] << " ± "
            << r.lens.std_dev[4 + i] << ", truth " << r.true_lens.distortion[i];

    // The pose: far better than the nominal set-up, and consistent with the lens — the recovered
    // camera puts the scene on the truth's pixel grid to a fraction of a pixel.
    EXPECT_EQ(r.control_points, 36);               // the four corners of the nine panels
    EXPECT_GT(r.nominal_rotation_error_deg, 0.5);  // there was a pose error to find
    EXPECT_GT(r.nominal_position_error_m, 0.05);
    EXPECT_LT(r.position_error_m, 0.5 * r.nominal_position_error_m);
    EXPECT_LT(r.rotation_error_deg, 0.5 * r.nominal_rotation_error_deg);
    EXPECT_LT(worst_px, 0.3);

    // The files a field user would have, readable by the commands that follow.
    EXPECT_EQ(read_camera_model(r.lens_file).fx, r.lens.fx);
    EXPECT_NEAR(read_camera_pose(r.pose_file).position_m().x(), r.pose.position_m().x(), 1e-9);
}

}  // namespace
}  // namespace tirpol::twin
