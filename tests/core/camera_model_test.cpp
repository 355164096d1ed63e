// Camera model and pose files: round trip, readable by OpenCV's own FileStorage, and clear errors.

#include "tirpol/core/camera_model.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/core.hpp>

#include "sample_camera_model.h"
#include "test_support.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/error.h"

namespace tirpol {
namespace {

CameraModel sample_model() {
    CameraModel m = test::sample_camera_model();
    m.distortion = {-0.31, 0.12, 0.0008, -0.0004, -0.02};
    m.rms_px = 0.07;
    m.views = 15;
    m.std_dev = {0.5, 0.5, 0.2, 0.2, 0.001, 0.003, 0.0001, 0.0001, 0.004};
    m.target = "checkerboard:9x6:0.06";
    return m;
}

TEST(CameraModelFile, RoundTripsAndOpenCvReadsIt) {
    test::TempDir dir;
    const CameraModel m = sample_model();
    write_camera_model(dir / "cam.yaml", m);
    const CameraModel back = read_camera_model(dir / "cam.yaml");
    EXPECT_EQ(back.width, 640);
    EXPECT_EQ(back.fx, m.fx);
    EXPECT_EQ(back.cy, m.cy);
    EXPECT_EQ(back.distortion, m.distortion);
    EXPECT_EQ(back.std_dev, m.std_dev);
    EXPECT_EQ(back.target, m.target);
    // A user's OpenCV program reads the same file without tirpol.
    cv::FileStorage fs((dir / "cam.yaml").string(), cv::FileStorage::READ);
    ASSERT_TRUE(fs.isOpened());
    cv::Mat k, d;
    fs["camera_matrix"] >> k;
    fs["distortion_coefficients"] >> d;
    EXPECT_EQ(k.at<double>(0, 2), m.cx);
    EXPECT_EQ(d.total(), 5u);
    EXPECT_EQ(d.at<double>(4), m.distortion[4]);
}

TEST(CameraModelFile, PoseRoundTrips) {
    test::TempDir dir;
    CameraPose p;
    p.camera_from_world =
        Eigen::AngleAxisd(0.3, Vec3(0.2, 0.9, -0.1).normalized()).toRotationMatrix();
    p.translation_m = Vec3(0.5, -1.0, 9.8);
    p.points = 8;
    p.rms_px = 0.2;
    write_camera_pose(dir / "pose.yaml", p);
    const CameraPose back = read_camera_pose(dir / "pose.yaml");
    EXPECT_LT((back.camera_from_world - p.camera_from_world).norm(), 1e-15);
    EXPECT_LT((back.position_m() - p.position_m()).norm(), 1e-12);
}

// Inputs the fuzzer found (a 48 GB allocation, cv::Exception, std::length_error, OpenCV's parser
// that never returned on a '%' followed by '---' or by '--'): each is refused with a tirpol::Error
// naming the file. The files are read by yaml-cpp now; no input reaches OpenCV's YAML parser.
TEST(CameraModelFile, FuzzRegressionsAreRefusedWithAnError) {
    const auto dir = test::source_dir() / "tests/data/fuzz-regressions/camera_geometry";
    int files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        ++files;
        try {
            read_camera_model(entry.path());
            ADD_FAILURE() << entry.path() << " was accepted";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(entry.path().filename().string()),
                      std::string::npos)
                << e.what();
        }
    }
    EXPECT_GE(files, 5);
}

// What OpenCV itself writes, as a user's calibration script would (cv::FileStorage, a float matrix,
// long data lists that OpenCV wraps over several lines), reads back through yaml-cpp unchanged.
TEST(CameraModelFile, ReadsWhatOpenCvWrites) {
    test::TempDir dir;
    const auto path = dir / "opencv.yaml";
    {
        cv::FileStorage fs(path.string(), cv::FileStorage::WRITE);
        fs << "image_width" << 320 << "image_height" << 256;
        fs << "camera_matrix"
           << (cv::Mat_<float>(3, 3) << 400.5f, 0.f, 159.5f, 0.f, 401.25f, 127.5f, 0.f, 0.f, 1.f);
        fs << "distortion_coefficients"
           << (cv::Mat_<double>(1, 8) << -0.31, 0.12, 1.5e-3, -2.5e-4, -0.021, 0.0, 0.0, 1.0 / 3.0);
        fs << "target"
           << "checkerboard:9x6:0.04";
    }
    ASSERT_EQ(read_file(path).rfind("%YAML:1.0", 0), 0u) << "OpenCV's own directive line";
    const CameraModel m = read_camera_model(path);
    EXPECT_EQ(m.width, 320);
    EXPECT_EQ(m.fx, 400.5);
    EXPECT_EQ(m.fy, 401.25);
    EXPECT_EQ(m.cy, 127.5);
    ASSERT_EQ(m.distortion.size(), 8u);
    EXPECT_EQ(m.distortion_model(), "rational");
    EXPECT_EQ(m.distortion[0], -0.31);
    EXPECT_EQ(m.distortion[7], 1.0 / 3.0);  // OpenCV writes 17 significant digits: exact round trip
    EXPECT_EQ(m.target, "checkerboard:9x6:0.04");
}

// The input that made OpenCV's parser loop for ever ('%' then '--', issue's 177 bytes) and variants
// of it: each returns, and with an error naming the file and the line.
TEST(CameraModelFile, PercentSignsAnywhereReturnWithAnError) {
    test::TempDir dir;
    const std::string body =
        "image_width: 640\nimage_height: 480\ncamera_matrix: !!opencv-matrix\n   rows: 3\n   cols: "
        "3\n   dt: d\n";
    for (const std::string tail :
         {"  -#%--\n", "  %---\n", "%\n---\n", "  - %--\n", "%TAG ! x\n--\n"}) {
        test::write_text(dir / "pct.yaml", "%YAML:1.0\n---\n" + body + tail);
        try {
            (void)read_camera_model(dir / "pct.yaml");
            ADD_FAILURE() << "accepted: " << tail;
        } catch (const Error& e) {
            EXPECT_THAT(std::string(e.what()), testing::HasSubstr("pct.yaml:")) << tail;
        }
    }
}

TEST(CameraModelFile, BadFilesNameTheField) {
    test::TempDir dir;
    auto expect_error = [&](const std::string& text, const std::string& needle) {
        test::write_text(dir / "bad.yaml", text);
        try {
            read_camera_model(dir / "bad.yaml");
            FAIL() << "accepted: " << text;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find("bad.yaml"), std::string::npos) << e.what();
        }
    };
    expect_error("%YAML:1.0\n---\nimage_width: 640\n", "image_height");
    expect_error("%YAML:1.0\n---\nimage_width: 640\nimage_height: 512\n", "camera_matrix");
    expect_error(
        "%YAML:1.0\n---\nimage_width: 640\nimage_height: 512\ncamera_matrix: !!opencv-matrix\n  "
        "rows: 3\n  cols: 3\n"
        "  dt: d\n  data: [ 700., 0., 320., 0., 700., 256., 0., 0., 1. ]\ndistortion_coefficients: "
        "!!opencv-matrix\n"
        "  rows: 1\n  cols: 4\n  dt: d\n  data: [ 0., 0., 0., 0. ]\n",
        "distortion_coefficients");
    expect_error(
        "%YAML:1.0\n---\nimage_width: 640\nimage_height: 512\ncamera_matrix: !!opencv-matrix\n  "
        "rows: 3\n  cols: 3\n"
        "  dt: d\n  data: [ -700., 0., 320., 0., 700., 256., 0., 0., 1. "
        "]\ndistortion_coefficients: !!opencv-matrix\n"
        "  rows: 1\n  cols: 5\n  dt: d\n  data: [ 0., 0., 0., 0., 0. ]\n",
        "fx");
    expect_error("just: text\n", "bad.yaml");
}

}  // namespace
}  // namespace tirpol
