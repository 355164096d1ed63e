#pragma once
// Frames of a heated target rendered through a known lens, and the check that a calibration
// recovered that lens (the twin's tolerances, docs/camera-geometry.md): shared by the checkerboard
// and circle-grid tests.

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <vector>

#include "heated_board.h"
#include "test_support.h"
#include "tirpol/calibration/geometric_calibration.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/simulation/renderer.h"
#include "tirpol/simulation/scene.h"
#include "truth_lens.h"

namespace tirpol::test {

using simulation::BoardView;

struct RenderedFrames {
    std::vector<std::filesystem::path> frames;  ///< S0 EXRs
    std::vector<Image> images;
};

/// Renders `board` through truth_lens() from each view into `dir` (S0 only, as a camera delivers
/// it).
inline RenderedFrames render_views(const TempDir& dir, const HeatedBoard& board,
                                   const std::vector<BoardView>& views, int spp) {
    write_camera_model(dir / "truth_lens.yaml", truth_lens());
    const std::string object = board.write(dir.path());
    RenderedFrames out;
    for (std::size_t i = 0; i < views.size(); ++i) {
        const auto scene_path = dir / fmt::format("view{:02}.yaml", i);
        write_text(scene_path, board_scene(object, "truth_lens.yaml", views[i].position,
                                           views[i].look_at, views[i].up, spp));
        const simulation::Scene scene = simulation::load_scene(scene_path);
        // Precondition of the test design: every feature point is in the frame with a margin.
        for (const Vec3& feature : board.features()) {
            const auto px = scene.camera.project(feature);
            EXPECT_TRUE(px && px->x() > 12 && px->y() > 12 && px->x() < 628 && px->y() < 500)
                << "view " << i;
        }
        Image image = simulation::render(scene);
        Image frame(image.width(), image.height());
        frame.set_channel("S0", image.channel("S0"));
        out.frames.push_back(dir / fmt::format("frame{:02}.exr", i));
        write_exr(out.frames.back(), frame);
        out.images.push_back(std::move(frame));
    }
    return out;
}

/// fx fy cx cy within the 0.5 %, k1 k2 p1 p2 k3 within 2 of their reported σ, RMS below
/// `max_rms_px`, every one of `views` used.
inline void expect_recovered(const calibration::GeometricCalibrationResult& r, int views,
                             double max_rms_px) {
    const CameraModel truth = truth_lens();
    const CameraModel& m = r.model;
    EXPECT_EQ(m.views, views);
    EXPECT_LT(m.rms_px, max_rms_px);
    EXPECT_NEAR(m.fx, truth.fx, 0.005 * truth.fx);
    EXPECT_NEAR(m.fy, truth.fy, 0.005 * truth.fy);
    EXPECT_NEAR(m.cx, truth.cx, 0.005 * truth.cx);
    EXPECT_NEAR(m.cy, truth.cy, 0.005 * truth.cy);
    for (std::size_t i = 0; i < 5; ++i)
        EXPECT_LT(std::abs(m.distortion[i] - truth.distortion[i]), 2.0 * m.std_dev[4 + i])
            << r.parameter_names[4 + i] << " = " << m.distortion[i] << " ± " << m.std_dev[4 + i]
            << ", truth " << truth.distortion[i];
}

}  // namespace tirpol::test
