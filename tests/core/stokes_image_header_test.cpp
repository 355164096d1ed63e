// The typed header attributes modules exchange: a round trip through an EXR file keeps every field
// (and the on-disk types other readers expect), and a present attribute of the wrong type or shape
// is an error naming it and the file.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "error_of.h"
#include "test_support.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"

using ::testing::AllOf;
using ::testing::HasSubstr;
using tirpol::test::error_of;

namespace tirpol {
namespace {

// Values a float holds exactly: EXR keeps lists of reals as 32-bit floats.
StokesImageHeader full_header() {
    return {.units = "W/(m^2 sr) band radiance",
            .band_um = std::array{8.0, 14.0},
            .variance_dof = 15,
            .variance_note = "includes the truth render's variance",
            .std_includes = "temporal noise",
            .calibration_range = CalibrationRangeAttribute{{283.5, 343.25}, 0.125},
            .analyzer_angles_deg = std::vector{0.0, 45.0, 90.0, 135.0},
            .fpa_temperature_k = 301.123456789,
            .camera_intrinsics_px = std::array{80.5, 81.25, 31.5, 23.5},
            .camera_distortion = std::vector{-0.125, 0.0078125, 0.0, 0.0, 0.0}};
}

Image small_image() {
    Image image(3, 2);
    image.add_channel("S0", 1.0f);
    return image;
}

TEST(StokesImageHeader, RoundTripThroughAnExrFileKeepsEveryField) {
    test::TempDir dir;
    Image image = small_image();
    const StokesImageHeader written = full_header();
    write_stokes_image_header(image, written);
    write_exr(dir / "h.exr", image);
    const Image back = read_exr(dir / "h.exr");
    const StokesImageHeader read = read_stokes_image_header(back, "h.exr");
    EXPECT_EQ(read.units, written.units);
    EXPECT_EQ(read.band_um, written.band_um);
    EXPECT_EQ(read.variance_dof, written.variance_dof);
    EXPECT_EQ(read.variance_note, written.variance_note);
    EXPECT_EQ(read.std_includes, written.std_includes);
    ASSERT_TRUE(read.calibration_range);
    EXPECT_EQ(read.calibration_range->range_k, written.calibration_range->range_k);
    EXPECT_EQ(read.calibration_range->outside_fraction,
              written.calibration_range->outside_fraction);
    EXPECT_EQ(read.analyzer_angles_deg, written.analyzer_angles_deg);
    EXPECT_EQ(read.fpa_temperature_k, written.fpa_temperature_k);  // an EXR double: exact
    EXPECT_EQ(read.camera_intrinsics_px, written.camera_intrinsics_px);
    EXPECT_EQ(read.camera_distortion, written.camera_distortion);
    // The on-disk types files written before this header have: older files still read.
    const Attributes& a = back.attributes();
    EXPECT_TRUE(std::holds_alternative<int>(a.at("variance_dof")));
    EXPECT_TRUE(std::holds_alternative<std::vector<double>>(a.at("band_um")));
    EXPECT_TRUE(std::holds_alternative<double>(a.at("calibration_outside_range_fraction")));
}

TEST(StokesImageHeader, AbsentFieldsAreNeitherReadNorWritten) {
    Image image = small_image();
    image.attributes()["units"] = std::string("counts");
    const StokesImageHeader none = read_stokes_image_header(small_image(), "empty");
    EXPECT_FALSE(none.units || none.band_um || none.variance_dof || none.variance_note ||
                 none.std_includes || none.calibration_range || none.analyzer_angles_deg ||
                 none.fpa_temperature_k || none.camera_intrinsics_px || none.camera_distortion);
    write_stokes_image_header(image, {.variance_dof = 3});
    EXPECT_EQ(image.attributes().size(), 2u);
    EXPECT_EQ(read_stokes_image_header(image, "image").units, "counts");  // left as it was
}

TEST(StokesImageHeader, WrongTypeOrShapeNamesTheAttributeAndTheFile) {
    test::TempDir dir;
    const auto error_in_file = [&](const std::string& name, AttributeValue value) {
        Image image = small_image();
        image.attributes()[name] = std::move(value);
        write_exr(dir / "bad.exr", image);
        const Image back = read_exr(dir / "bad.exr");
        return error_of([&] { read_stokes_image_header(back, (dir / "bad.exr").string()); });
    };
    const std::string file = (dir / "bad.exr").string();
    // calibration/microgrid_run wrote the band as text before.
    EXPECT_THAT(error_in_file("band_um", std::string("8 14")),
                AllOf(HasSubstr(file), HasSubstr("'band_um'"), HasSubstr("2 reals")));
    EXPECT_THAT(error_in_file("band_um", std::vector<double>{14.0, 8.0}),
                AllOf(HasSubstr(file), HasSubstr("'band_um'"), HasSubstr("0 < LO < HI")));
    EXPECT_THAT(error_in_file("variance_dof", 3.5),
                AllOf(HasSubstr(file), HasSubstr("'variance_dof'"), HasSubstr("an integer")));
    EXPECT_THAT(error_in_file("std_includes", 1),
                AllOf(HasSubstr(file), HasSubstr("'std_includes'"), HasSubstr("text")));
    EXPECT_THAT(error_in_file("camera_intrinsics_px", std::vector<double>{80.0, 80.0, 31.5}),
                AllOf(HasSubstr("'camera_intrinsics_px'"), HasSubstr("got 3 value(s)")));
    // The range and its outside fraction are written together; one alone is a damaged header.
    EXPECT_THAT(error_in_file("calibration_outside_range_fraction", 0.5),
                AllOf(HasSubstr(file), HasSubstr("'calibration_range_k'"),
                      HasSubstr("only 'calibration_outside_range_fraction'")));
}

}  // namespace
}  // namespace tirpol
