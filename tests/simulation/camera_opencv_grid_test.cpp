// The simulated camera lands on OpenCV's pixel grid: what cv::projectPoints says about a world
// point is where the renderer's rays go and where the rendered image shows it.

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/calib3d.hpp>

#include "scene_fixtures.h"
#include "tirpol/core/camera_model.h"
#include "tirpol/core/error.h"
#include "tirpol/simulation/pinhole_camera.h"
#include "truth_lens.h"

namespace tirpol::simulation {
namespace {

CameraPose some_pose() {
    CameraPose p;
    const Mat3 w = PinholeCamera::look_at(Vec3(0.3, -9.5, 1.6), Vec3(0.5, 0.0, 0.8), world_up());
    p.camera_from_world = w.transpose();
    p.translation_m = -p.camera_from_world * Vec3(0.3, -9.5, 1.6);
    return p;
}

std::vector<cv::Point2d> opencv_projection(const CameraModel& m, const CameraPose& pose,
                                           const std::vector<Vec3>& world) {
    cv::Mat r(3, 3, CV_64F), rvec, tvec(3, 1, CV_64F);
    for (int i = 0; i < 3; ++i) {
        tvec.at<double>(i) = pose.translation_m[i];
        for (int j = 0; j < 3; ++j) r.at<double>(i, j) = pose.camera_from_world(i, j);
    }
    cv::Rodrigues(r, rvec);
    std::vector<cv::Point3d> pts;
    for (const Vec3& p : world) pts.emplace_back(p.x(), p.y(), p.z());
    std::vector<cv::Point2d> out;
    const cv::Mat k = (cv::Mat_<double>(3, 3) << m.fx, 0, m.cx, 0, m.fy, m.cy, 0, 0, 1);
    cv::projectPoints(pts, rvec, tvec, k, cv::Mat(m.distortion, true), out);
    return out;
}

TEST(CameraOpenCvGrid, RaysGoWhereProjectPointsSays) {
    const CameraModel model = tirpol::test::truth_lens();
    const CameraPose pose = some_pose();
    const PinholeCamera camera = PinholeCamera::from_model(model, pose);
    // World points spread over the whole image, corners included (where the distortion is
    // strongest).
    std::vector<Vec3> world;
    for (int i = -4; i <= 4; ++i)
        for (int j = -3; j <= 3; ++j)
            world.push_back(Vec3(0.5 + 0.8 * i, 0.5 * (i + j), 0.8 + 0.55 * j));
    const auto cv_px = opencv_projection(model, pose, world);
    int inside = 0;
    for (std::size_t i = 0; i < world.size(); ++i) {
        const auto ours = camera.project(world[i]);
        ASSERT_TRUE(ours.has_value());
        // The renderer's pixel coordinates have the corner origin: OpenCV's (u, v) is (u + ½, v +
        // ½) here.
        EXPECT_NEAR(ours->x(), cv_px[i].x + 0.5, 1e-9);
        EXPECT_NEAR(ours->y(), cv_px[i].y + 0.5, 1e-9);
        if (cv_px[i].x < -0.5 || cv_px[i].y < -0.5 || cv_px[i].x > 639.5 || cv_px[i].y > 511.5)
            continue;
        ++inside;
        // The ray through that image point passes through the world point.
        const Vec3 d = camera.ray_direction(cv_px[i].x + 0.5, cv_px[i].y + 0.5);
        const Vec3 to_point = (world[i] - camera.position()).normalized();
        EXPECT_LT(std::atan2(d.cross(to_point).norm(), d.dot(to_point)), 1e-10)
            << "point " << i << " at " << cv_px[i];
    }
    EXPECT_GT(inside, 40) << "the test points must cover the image";
}

TEST(CameraOpenCvGrid, InverseIsExactAtTheCornersOfAStrongLens) {
    // k1 = −0.45: fixed-point iteration alone (cv::undistortPoints' default) leaves ~0.01 px here.
    CameraModel m = tirpol::test::truth_lens();
    m.distortion = {-0.45, 0.25, 0.001, 0.001, -0.08};
    for (const Vec2& px :
         {Vec2(-0.5, -0.5), Vec2(639.5, 511.5), Vec2(0.0, 400.0), Vec2(320.0, 256.0)}) {
        const Vec2 x = m.undistort(px);
        EXPECT_LT((m.project(Vec3(x.x(), x.y(), 1.0)) - px).norm(), 1e-9) << px.transpose();
    }
}

TEST(CameraOpenCvGrid, RenderedHotSpotsLandOnProjectPointsPixels) {
    // Small hot discs facing the camera in front of a cold wall; the intensity centroid of each
    // disc in the render must sit where cv::projectPoints puts its centre (OpenCV convention: pixel
    // x has its centre at x). Discs of ~3 px radius: their centroid is biased by the distortion by
    // < 0.01 px. The centroids scatter by up to 0.035 px with the seed (seeds 3–5, 64 spp, 30
    // coordinates, with independent or stratified sub-pixel positions alike), so 0.05 px; a
    // half-pixel convention slip would be 0.5 px.
    tirpol::test::TempDir dir;
    CameraModel model = tirpol::test::truth_lens();
    model.width = 160;
    model.height = 128;
    model.fx = 190.0;
    model.fy = 191.0;
    model.cx = 83.3;
    model.cy = 61.8;
    write_camera_model(dir / "lens.yaml", model);
    const std::vector<Vec3> centres = {Vec3(0, 0, 1), Vec3(-2.2, 0, 2.5), Vec3(2.4, 0, -0.4),
                                       Vec3(-2.6, 0, -0.6), Vec3(2.0, 0, 2.2)};
    std::string objects =
        "  - {name: wall, geometry: {type: plane, size: [40, 40]}, transform: {rotate_deg: [90, 0, "
        "0], translate: [0, 1, 0]}, material: " +
        std::string(simulation::test::kGreyDiffuse) + ", temperature: 250}\n";
    for (const Vec3& c : centres)
        objects += fmt::format(
            "  - {{name: spot, geometry: {{type: disk, radius: 0.12, segments: 64}}, transform: "
            "{{rotate_deg: [90, 0, 0], "
            "translate: [{}, {}, {}]}}, material: {}, temperature: 350}}\n",
            c.x(), c.y(), c.z(), simulation::test::kGreyDiffuse);
    const std::string yaml = fmt::format(
        "band: {{lo_um: 8, hi_um: 14}}\nsampling: {{spp: 64, max_bounces: 0, seed: "
        "3}}\nmaterials_dir: {}\n"
        "camera: {{model: lens.yaml, position: [0.1, -8, 1.2], look_at: [0, 0, 1]}}\nsky: {{type: "
        "uniform, temperature: 200}}\n"
        "objects:\n{}",
        (tirpol::test::source_dir() / "config" / "materials").string(), objects);
    const Scene scene = simulation::test::load_scene_text(dir, yaml);
    ASSERT_EQ(scene.camera.width(), 160);
    const Image image = render(scene);
    const auto& s0 = image.channel("S0");
    const auto cv_px = opencv_projection(model, scene.camera.pose(), centres);
    float background = s0[0];
    for (std::size_t i = 0; i < centres.size(); ++i) {
        double sum = 0, sx = 0, sy = 0;
        const int x0 = static_cast<int>(std::lround(cv_px[i].x)),
                  y0 = static_cast<int>(std::lround(cv_px[i].y));
        for (int y = y0 - 8; y <= y0 + 8; ++y)
            for (int x = x0 - 8; x <= x0 + 8; ++x) {
                ASSERT_TRUE(x >= 0 && y >= 0 && x < 160 && y < 128)
                    << "spot " << i << " too close to the border";
                const double w =
                    std::max(0.0, static_cast<double>(s0[image.index(x, y)] - background));
                sum += w;
                sx += w * x;  // pixel x's centre is at OpenCV coordinate x
                sy += w * y;
            }
        ASSERT_GT(sum, 0.0);
        EXPECT_NEAR(sx / sum, cv_px[i].x, 0.05) << "spot " << i;
        EXPECT_NEAR(sy / sum, cv_px[i].y, 0.05) << "spot " << i;
    }
}

TEST(CameraOpenCvGrid, SceneModelAndPoseFilesAreRead) {
    tirpol::test::TempDir dir;
    write_camera_model(dir / "lens.yaml", tirpol::test::truth_lens());
    write_camera_pose(dir / "pose.yaml", some_pose());
    const PinholeCamera camera = PinholeCamera::from_config(
        ConfigNode::parse("{model: lens.yaml, pose: pose.yaml}", (dir / "scene.yaml").string()));
    EXPECT_EQ(camera.width(), 640);
    EXPECT_NEAR((camera.position() - Vec3(0.3, -9.5, 1.6)).norm(), 0.0, 1e-12);
    EXPECT_NEAR(camera.lens_model().cx, 331.7, 1e-12);
    EXPECT_EQ(camera.lens_model().distortion.size(), 5u);
    try {
        PinholeCamera::from_config(ConfigNode::parse(
            "{model: lens.yaml, fov_deg: 30, pose: pose.yaml}", (dir / "scene.yaml").string()));
        FAIL() << "model and fov_deg together must be refused";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("fov_deg"), std::string::npos) << e.what();
    }
    try {
        PinholeCamera::from_config(
            ConfigNode::parse("{model: lens.yaml, resolution: [320, 256], pose: pose.yaml}",
                              (dir / "scene.yaml").string()));
        FAIL() << "a resolution that contradicts the model must be refused";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("640x512"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace tirpol::simulation
