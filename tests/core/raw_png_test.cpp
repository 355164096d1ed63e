// 16-bit raw PNGs are decoded with libpng directly (core/src/png_read.cpp): chunks that cannot
// change a count (a text chunk with a wrong CRC, a colour profile that is not zlib data) must
// neither reach stderr — OpenCV's decoder let libpng print "libpng warning: ..." — nor
// alter the counts. The file is fuzz/make_seeds.py's regression input
// raw_image/ancillary_chunk_warnings.png: counts 18000 + x + 100·y, 4×3.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "test_support.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"

namespace tirpol {
namespace {

const std::filesystem::path kNoisyPng =
    test::source_dir() / "tests/data/fuzz-regressions/raw_image/ancillary_chunk_warnings.png";

TEST(RawPng, TheRegressionFileDoesMakeLibpngWarnThroughOpenCv) {
    // Guards the next test: without this, a file that triggers no warning would pass it vacuously.
    testing::internal::CaptureStderr();
    (void)cv::imread(kNoisyPng.string(), cv::IMREAD_UNCHANGED);
    EXPECT_THAT(testing::internal::GetCapturedStderr(), testing::HasSubstr("libpng warning"));
}

TEST(RawPng, AncillaryChunkTroubleIsSilentAndTheCountsAreExact) {
    testing::internal::CaptureStderr();
    const Image image = read_raw_image(kNoisyPng, "counts");
    EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
    ASSERT_EQ(image.width(), 4);
    ASSERT_EQ(image.height(), 3);
    const auto& counts = image.channel("counts");
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 4; ++x)
            EXPECT_EQ(counts[static_cast<std::size_t>(y * 4 + x)], 18000.0f + x + 100.0f * y);
    EXPECT_EQ(std::get<int>(image.attributes().at("source_depth_bits")), 16);
}

TEST(RawPng, RoundTripsWhatOpenCvWritesIncludingTheFullSixteenBitRange) {
    const test::TempDir dir;
    cv::Mat written(5, 7, CV_16UC1);
    for (int y = 0; y < written.rows; ++y)
        for (int x = 0; x < written.cols; ++x)
            written.at<std::uint16_t>(y, x) =
                static_cast<std::uint16_t>(x == 6 ? 65535 - y : x * 9000 + y);
    ASSERT_TRUE(cv::imwrite((dir / "counts.png").string(), written));
    const Image image = read_raw_image(dir / "counts.png", "counts");
    const auto& counts = image.channel("counts");
    for (int y = 0; y < written.rows; ++y)
        for (int x = 0; x < written.cols; ++x)
            EXPECT_EQ(counts[static_cast<std::size_t>(y * written.cols + x)],
                      static_cast<float>(written.at<std::uint16_t>(y, x)));
}

TEST(RawPng, ColourAndTruncatedPngsAreErrorsNamingTheFile) {
    const test::TempDir dir;
    ASSERT_TRUE(cv::imwrite((dir / "rgb.png").string(),
                            cv::Mat(3, 4, CV_16UC3, cv::Scalar(1000, 2000, 3000))));
    try {
        (void)read_raw_image(dir / "rgb.png", "counts");
        ADD_FAILURE() << "an RGB PNG was read as counts";
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), testing::AllOf(testing::HasSubstr("rgb.png"),
                                             testing::HasSubstr("3 channels")));
    }
    const std::string whole = read_file(kNoisyPng);
    test::write_text(dir / "cut.png", whole.substr(0, whole.size() - 30));  // into the IDAT chunk
    testing::internal::CaptureStderr();
    try {
        (void)read_raw_image(dir / "cut.png", "counts");
        ADD_FAILURE() << "a truncated PNG was read";
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), testing::AllOf(testing::HasSubstr("cut.png"),
                                             testing::HasSubstr("cannot be decoded")));
    }
    EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
}

}  // namespace
}  // namespace tirpol
