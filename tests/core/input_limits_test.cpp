// Declared sizes are checked before allocating and bit depths before interpreting pixels (before:
// a 480 KB EXR declaring 40000×40000 made `info` use 4.5 GB; an 8-bit PNG gave all-NaN
// temperatures). The inputs are the regression files kept in tests/data/fuzz-regressions/,
// written by fuzz/make_seeds.py.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "error_of.h"
#include "test_support.h"
#include "tirpol/core/camera_model.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/image.h"
#include "tirpol/core/limits.h"
#include "tirpol/core/radiometry.h"

using tirpol::test::error_of;

namespace tirpol {
namespace {

std::filesystem::path regression(const std::string& target, const std::string& name) {
    return test::source_dir() / "tests/data/fuzz-regressions" / target / name;
}

TEST(InputLimits, ExrDeclaringHugeSizeIsRefusedBeforeAllocating) {
    const auto huge = regression("exr", "declares_40000x40000.exr");
    EXPECT_THAT(error_of([&] { read_exr(huge); }),
                testing::AllOf(testing::HasSubstr("declares_40000x40000.exr"),
                               testing::HasSubstr("16384")));
    // Within the side limit but far more pixels than a 400-byte file can hold under any
    // compression.
    const auto liar = regression("exr", "declares_4000x4000_in_tiny_file.exr");
    EXPECT_THAT(error_of([&] { read_exr(liar); }),
                testing::AllOf(testing::HasSubstr("4000×4000"),
                               testing::HasSubstr("no OpenEXR compression")));
}

TEST(InputLimits, ExrAttributeDeclaringMoreBytesThanTheFileIsRefusedBeforeOpenExrAllocatesIt) {
    const auto path = regression("exr", "attribute_declares_1_6_GB.exr");
    EXPECT_THAT(error_of([&] { read_exr(path); }),
                testing::AllOf(testing::HasSubstr("attribute_declares_1_6_GB.exr"),
                               testing::HasSubstr("'junk'"),
                               testing::HasSubstr("declares 1634231040 bytes")));
}

TEST(InputLimits, ExrPixelCountIsBoundedByTheFilesOwnCompression) {
    // Uncompressed, a file holds every decoded byte: 64×64 floats (16 KB) cannot fit in < 1 KB.
    const auto path = regression("exr", "uncompressed_declares_64x64_without_pixels.exr");
    EXPECT_THAT(error_of([&] { read_exr(path); }),
                testing::AllOf(testing::HasSubstr("64×64"), testing::HasSubstr("at most 1:1")));
    // The ZIP bound (deflate's 1032:1) must not refuse the best case a real file reaches: a
    // constant 2048×2048 image, written by OpenEXR's own ZIP compressor.
    const test::TempDir dir;
    Image flat(2048, 2048);
    flat.add_channel("S0");
    write_exr(dir / "flat.exr", flat);
    EXPECT_EQ(read_exr(dir / "flat.exr").width(), 2048);
}

TEST(InputLimits, CameraModelMatrixIsCheckedAgainstItsDataBeforeOpenCvAllocatesIt) {
    // The fuzzer's `cols:` was a stray byte (0xD5) that OpenCV read as 48 GB of columns; it is now
    // named where it stands, before any parsing.
    const auto path = regression("camera_geometry", "matrix_cols_not_a_number.yaml");
    EXPECT_THAT(
        error_of([&] { (void)read_camera_model(path); }),
        testing::HasSubstr("matrix_cols_not_a_number.yaml:7:10: invalid UTF-8 (byte 0xD5)"));
    const test::TempDir dir;
    test::write_text(
        dir / "cols.yaml",
        "%YAML:1.0\n---\nimage_width: 64\nimage_height: 48\ncamera_matrix: !!opencv-matrix\n"
        "   rows: 3\n   cols: many\n   dt: d\n   data: [ 80., 0., 31.5, 0., 80., 23.5, 0., 0., 1. "
        "]\n");
    EXPECT_THAT(
        error_of([&] { (void)read_camera_model(dir / "cols.yaml"); }),
        testing::AllOf(testing::HasSubstr("cols.yaml:7:"), testing::HasSubstr("camera_matrix.cols"),
                       testing::HasSubstr("expected an integer")));
    test::write_text(
        dir / "short.yaml",
        "%YAML:1.0\n---\nimage_width: 64\nimage_height: 48\ncamera_matrix: !!opencv-matrix\n"
        "   rows: 3\n   cols: 3\n   dt: d\n   data: [ 80., 0., 31.5, 0., 80., 23.5, 0., 0. ]\n");
    EXPECT_THAT(error_of([&] { (void)read_camera_model(dir / "short.yaml"); }),
                testing::HasSubstr("declares 3x3 values but its data holds 8"));
    // The translation's value is cut off in the middle of a flow list: a YAML syntax error, named
    // with the file and the line and column of the broken value (line 9, under translation_m).
    EXPECT_THAT(
        error_of([&] {
            (void)read_camera_pose(regression("camera_geometry", "matrix_field_is_a_list.yaml"));
        }),
        testing::AllOf(testing::HasSubstr("matrix_field_is_a_list.yaml:9:"),
                       testing::HasSubstr("YAML syntax error")));
}

TEST(InputLimits, ExrWithNonUtf8AttributeStillReads) {
    const Image im = read_exr(regression("exr", "non_utf8_attribute.exr"));
    EXPECT_EQ(im.width(), 2);
    EXPECT_EQ(std::get<std::string>(im.attributes().at("note")),
              "caf\xE9 \xFF\xFE");  // kept as is; sanitised on output
}

TEST(InputLimits, EightBitRawImagesAreRefusedWithTheReason) {
    for (const char* name : {"eight_bit.png", "tiff_bits_per_sample_8.tif"})
        EXPECT_THAT(error_of([&] { read_raw_image(regression("raw_image", name)); }),
                    testing::AllOf(testing::HasSubstr(name), testing::HasSubstr("8-bit"),
                                   testing::HasSubstr("cannot hold camera counts")));
    // PNG and TIFF headers are read before decoding (the TIFF, 130 bytes, was written by hand: one
    // IFD declaring a 40000×40000 16-bit strip image).
    for (const char* name : {"png_declares_40000x40000.png", "tiff_declares_40000x40000.tif"})
        EXPECT_THAT(error_of([&] { read_raw_image(regression("raw_image", name)); }),
                    testing::AllOf(testing::HasSubstr(name), testing::HasSubstr("40000×40000")));
}

TEST(InputLimits, ImagesBeyondTheLimitsAreErrorsNotBadAlloc) {
    EXPECT_THAT(error_of([] { Image(limits::kMaxImageSide + 1, 1); }),
                testing::HasSubstr("exceeds tirpol's limits"));
    EXPECT_THAT(error_of([] { Image(16000, 16000); }),
                testing::HasSubstr("exceeds tirpol's limits"));
    EXPECT_NO_THROW(Image(640, 512));
}

TEST(InputLimits, PhysicalRangesNameTheQuantity) {
    EXPECT_THAT(
        error_of([] { check_temperature_k(1e308, "--temperature-k"); }),
        testing::AllOf(testing::HasSubstr("--temperature-k"), testing::HasSubstr("[1, 10000] K")));
    EXPECT_THAT(error_of([] { check_temperature_k(0.5, "t"); }), testing::HasSubstr("outside"));
    EXPECT_DOUBLE_EQ(check_temperature_k(300.0, "t"), 300.0);
    EXPECT_THAT(
        error_of([] { check_finite(std::numeric_limits<double>::infinity(), "band radiance"); }),
        testing::HasSubstr("band radiance: the result is not a finite number"));
    EXPECT_THAT(error_of([] { check_non_negative(-1.0, "temperature_std_k"); }),
                testing::HasSubstr("≥ 0"));
}

TEST(InputLimits, RelativeSpectralResponseStaysRelative) {
    // Issue 20: an RSR value of 1e308 made every band radiance inf.
    EXPECT_THAT(
        error_of([] { SpectralResponse::load_csv(regression("rsr_csv", "response_1e308.csv")); }),
        testing::AllOf(testing::HasSubstr("response_1e308.csv"),
                       testing::HasSubstr("must lie in [0, 1]")));
    EXPECT_NO_THROW(
        SpectralResponse({8.0, 10.0, 12.0}, {0.0, 1.02, 0.5}));  // digitising noise at the peak
}

}  // namespace
}  // namespace tirpol
