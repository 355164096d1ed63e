// A radiometric calibration records the camera it was made with, and applying it to a session from
// another camera is refused unless forced (once another camera's calibration of the same size
// gave S0 = 203 W/(m²·sr) with exit 0). Per-pixel gains and offsets belong to one detector.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "test_support.h"
#include "tirpol/calibration/session_calibration.h"
#include "tirpol/calibration/synthetic_session.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"

namespace tirpol::calibration {
namespace {

class CameraIdentity : public testing::Test {
protected:
    static void SetUpTestSuite() {
        dir_ = new test::TempDir("tirpol-camera-identity");
        write_synthetic_sessions(dir_->path(), SyntheticCamera{},
                                 synthetic_panel_scene(64, 48, Band(8.0, 14.0)), Band(8.0, 14.0));
    }
    static void TearDownTestSuite() { delete dir_; }
    static std::filesystem::path root() { return dir_->path(); }
    /// A copy of the scene session whose manifest says another camera took it.
    static std::filesystem::path other_camera_session(const test::TempDir& tmp,
                                                      const std::string& field,
                                                      const nlohmann::json& value) {
        std::filesystem::copy(root() / "scene", tmp / "scene",
                              std::filesystem::copy_options::recursive);
        auto manifest = nlohmann::json::parse(read_file(tmp / "scene" / "session.json"));
        manifest["camera"][field] = value;
        write_file_atomic(tmp / "scene" / "session.json", manifest.dump());
        // The frames' headers name the camera too (read_session_frame compares them): another
        // camera's session says so in both places.
        if (field == "serial")
            for (const auto& entry :
                 std::filesystem::directory_iterator(tmp / "scene" / "frames")) {
                Image frame = read_exr(entry.path());
                frame.attributes()["camera_serial"] = value.get<std::string>();
                write_exr(entry.path(), frame);
            }
        return tmp / "scene";
    }
    static test::TempDir* dir_;
};
test::TempDir* CameraIdentity::dir_ = nullptr;

TEST_F(CameraIdentity, CalibrationFileRecordsTheCamera) {
    const auto cal = calibrate_radiometric_session(root() / "lab", Band(8.0, 14.0));
    ASSERT_TRUE(cal.camera.known());
    test::TempDir tmp;
    write_radiometric_calibration((tmp / "cal.exr").string(), cal);
    const auto back = read_radiometric_calibration((tmp / "cal.exr").string());
    EXPECT_EQ(back.camera.serial, cal.camera.serial);
    EXPECT_EQ(back.camera.model, cal.camera.model);
    EXPECT_EQ(back.camera.pixel_format, cal.camera.pixel_format);
    EXPECT_EQ(back.camera.bits_per_pixel, cal.camera.bits_per_pixel);
    EXPECT_NO_THROW(reduce_session(root() / "scene", back, nullptr));  // same camera: applies
}

TEST_F(CameraIdentity, AnotherCameraOfTheSameSizeIsRefusedNamingBoth) {
    const auto cal = calibrate_radiometric_session(root() / "lab", Band(8.0, 14.0));
    test::TempDir tmp;
    const auto session = other_camera_session(tmp, "serial", "OTHER-9999");
    try {
        reduce_session(session, cal, nullptr);
        FAIL() << "a calibration of another camera was applied";
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), testing::AllOf(testing::HasSubstr("another camera (serial differs)"),
                                             testing::HasSubstr("'" + cal.camera.serial + "'"),
                                             testing::HasSubstr("'OTHER-9999'"),
                                             testing::HasSubstr("--other-camera")));
    }
    EXPECT_THROW(calibrate_polarimetric_session(session, cal), Error);
    SessionReductionOptions forced;
    forced.force_other_camera = true;
    EXPECT_NO_THROW(reduce_session(session, cal, nullptr, forced));
}

TEST_F(CameraIdentity, BitDepthAndPixelFormatCount) {
    const auto cal = calibrate_radiometric_session(root() / "lab", Band(8.0, 14.0));
    test::TempDir a, b;
    EXPECT_THROW(reduce_session(other_camera_session(a, "bits_per_pixel", 8), cal, nullptr), Error);
    EXPECT_THROW(
        reduce_session(other_camera_session(b, "pixel_format", "Mono12Packed"), cal, nullptr),
        Error);
}

}  // namespace
}  // namespace tirpol::calibration
