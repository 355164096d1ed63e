// core's CameraModel projects exactly as OpenCV's calib3d does, for every distortion model, and
// undistort() inverts it (here because calibration's tests link calib3d).

#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>

#include "sample_camera_model.h"
#include "tirpol/core/camera_model.h"

namespace tirpol {
namespace {

CameraModel sample_model() { return test::sample_camera_model(); }

TEST(CameraModelOpenCv, ProjectMatchesOpenCvForEveryModel) {
    // Reference: cv::projectPoints (OpenCV calib3d) with the same coefficients, 5, 8 and 12 of
    // them.
    for (const std::vector<double>& dist :
         {std::vector<double>{-0.3, 0.1, 0.001, -0.002, -0.02},
          std::vector<double>{0.2, -0.05, 0.001, -0.002, 0.01, 0.5, -0.02, 0.03},
          std::vector<double>{0.2, -0.05, 0.001, -0.002, 0.01, 0.5, -0.02, 0.03, 0.001, -0.001,
                              0.002, 0.0005}}) {
        CameraModel m = sample_model();
        m.distortion = dist;
        const std::vector<cv::Point3d> pts = {
            {0.1, -0.2, 1.0}, {-0.4, 0.3, 1.2}, {0.35, 0.28, 0.9}};
        std::vector<cv::Point2d> expected;
        const cv::Mat k = (cv::Mat_<double>(3, 3) << m.fx, 0, m.cx, 0, m.fy, m.cy, 0, 0, 1);
        cv::projectPoints(pts, cv::Mat::zeros(3, 1, CV_64F), cv::Mat::zeros(3, 1, CV_64F), k,
                          cv::Mat(dist, true), expected);
        for (std::size_t i = 0; i < pts.size(); ++i) {
            const Vec2 p = m.project(Vec3(pts[i].x, pts[i].y, pts[i].z));
            EXPECT_NEAR(p.x(), expected[i].x, 1e-9);
            EXPECT_NEAR(p.y(), expected[i].y, 1e-9);
            const Vec2 back = m.undistort(p);
            EXPECT_NEAR(back.x(), pts[i].x / pts[i].z, 1e-12) << m.distortion_model();
            EXPECT_NEAR(back.y(), pts[i].y / pts[i].z, 1e-12) << m.distortion_model();
        }
    }
}

}  // namespace
}  // namespace tirpol
