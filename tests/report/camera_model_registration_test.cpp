// Registration by camera model: a simulation rendered through the measured camera's
// calibrated model is compared on the measured pixel grid without a warp; the header check refuses
// a simulation rendered through another lens, and the residual misalignment is still measured from
// the images (phase correlation, Kuglin & Hines 1975), so a pose error shows up as a shift.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "error_of.h"
#include "synthetic_pair.h"
#include "test_support.h"
#include "tirpol/core/error.h"
#include "tirpol/report/comparison_report.h"
#include "tirpol/report/registration.h"

using tirpol::test::error_of;

using namespace tirpol::report;
using ::testing::HasSubstr;

namespace {

tirpol::CameraModel lens_of(const tirpol::Image& image) {
    tirpol::CameraModel m;
    m.width = image.width();
    m.height = image.height();
    m.fx = 210.0, m.fy = 211.5, m.cx = 98.3, m.cy = 69.1;
    m.distortion = {-0.28, 0.11, 0.0007, -0.0004, 0.0};
    return m;
}

/// The attributes the renderer writes for `m` (simulation/src/renderer.cpp).
void stamp(tirpol::Image& simulated, const tirpol::CameraModel& m) {
    simulated.attributes()["camera_intrinsics_px"] = std::vector<double>{m.fx, m.fy, m.cx, m.cy};
    simulated.attributes()["camera_distortion"] =
        std::vector<double>(m.distortion.begin(), m.distortion.begin() + 4);
}

test::SyntheticPairOptions quiet(double dx) {
    test::SyntheticPairOptions o;
    o.shift_x_px = dx;
    o.measured_sigma = 0.02;
    o.simulated_sigma = 0.01;
    return o;
}

TEST(CameraModelRegistration, RenderedThroughTheModelIsComparedWithoutAWarp) {
    auto pair = test::make_synthetic_pair(quiet(0.0));
    const auto model = lens_of(pair.measured);
    stamp(pair.simulated, model);  // trailing k3 = 0 left out, as the renderer does
    const Registration reg =
        register_by_camera_model(pair.measured, pair.simulated, model, "cam.yaml");
    EXPECT_EQ(reg.method, RegistrationMethod::CameraModel);
    EXPECT_EQ(reg.model, "identity");
    EXPECT_EQ(reg.measured_to_simulated, (std::array<double, 9>{1, 0, 0, 0, 1, 0, 0, 0, 1}));
    EXPECT_LT(std::hypot(reg.residual_shift_px[0], reg.residual_shift_px[1]), 0.2);
    EXPECT_THAT(reg.note, HasSubstr("cam.yaml"));
    EXPECT_EQ(to_string(reg.method), "camera-model");
    EXPECT_EQ(parse_registration_method("camera-model"), RegistrationMethod::CameraModel);

    // Through compare(): the report states the method and its note.
    CompareOptions co;
    co.registration = RegistrationMethod::CameraModel;
    co.camera_model = model;
    co.camera_model_name = "cam.yaml";
    const Comparison c = compare(pair.measured, pair.simulated, co);
    EXPECT_EQ(c.result.registration.method, RegistrationMethod::CameraModel);
    EXPECT_THAT(c.result.registration.note, HasSubstr("no warp"));
}

TEST(CameraModelRegistration, APoseErrorShowsAsResidualMisalignment) {
    // The model is right but the pose is off: the images differ by 1.5 px; nothing is warped, the
    // shift is measured and reported.
    auto pair = test::make_synthetic_pair(quiet(1.5));
    const auto model = lens_of(pair.measured);
    stamp(pair.simulated, model);
    const Registration reg =
        register_by_camera_model(pair.measured, pair.simulated, model, "cam.yaml");
    EXPECT_EQ(reg.model, "identity");
    EXPECT_NEAR(std::abs(reg.residual_shift_px[0]), 1.5, 0.3);
    EXPECT_NEAR(reg.residual_shift_px[1], 0.0, 0.3);
}

TEST(CameraModelRegistration, AnotherLensOrAMissingHeaderOrSizeIsAnError) {
    auto pair = test::make_synthetic_pair(quiet(0.0));
    const auto model = lens_of(pair.measured);
    auto other = model;
    other.fx *= 1.01;
    stamp(pair.simulated, other);
    auto msg = error_of(
        [&] { register_by_camera_model(pair.measured, pair.simulated, model, "cam.yaml"); });
    EXPECT_THAT(msg, HasSubstr("cam.yaml"));
    EXPECT_THAT(msg, HasSubstr("intrinsics fx fy cx cy"));

    other = model;
    other.distortion[0] = -0.2;
    stamp(pair.simulated, other);
    msg = error_of(
        [&] { register_by_camera_model(pair.measured, pair.simulated, model, "cam.yaml"); });
    EXPECT_THAT(msg, HasSubstr("distortion"));

    pair.simulated.attributes().erase("camera_intrinsics_px");
    msg = error_of(
        [&] { register_by_camera_model(pair.measured, pair.simulated, model, "cam.yaml"); });
    EXPECT_THAT(msg, HasSubstr("header has no camera intrinsics fx fy cx cy"));

    auto small = model;
    small.width = 100;
    msg = error_of(
        [&] { register_by_camera_model(pair.measured, pair.simulated, small, "cam.yaml"); });
    EXPECT_THAT(msg, HasSubstr("the model is 100×"));

    // Asking for the method without a model.
    msg = error_of([&] {
        register_images(pair.measured, pair.simulated, RegistrationMethod::CameraModel, {});
    });
    EXPECT_THAT(msg, HasSubstr("--camera"));
}

}  // namespace
