// read_raw_image: 16-bit PNG and TIFF keep their integer counts unscaled; EXR channels; clear
// errors.

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "test_support.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"

namespace tirpol {
namespace {

TEST(RasterIo, SixteenBitPngAndTiffKeepRawCounts) {
    test::TempDir dir;
    cv::Mat m(3, 4, CV_16UC1);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 4; ++x)
            m.at<std::uint16_t>(y, x) = static_cast<std::uint16_t>(18109 + 1000 * y + x);
    for (const char* name : {"raw.png", "raw.tiff"}) {
        ASSERT_TRUE(cv::imwrite((dir / name).string(), m));
        const Image im = read_raw_image(dir / name);
        ASSERT_EQ(im.width(), 4);
        ASSERT_EQ(im.height(), 3);
        EXPECT_FLOAT_EQ(im.at("counts", 0, 0), 18109.0f) << name;
        EXPECT_FLOAT_EQ(im.at("counts", 3, 2), 20112.0f) << name;
    }
}

TEST(RasterIo, ExrChannelAndErrors) {
    test::TempDir dir;
    Image im(2, 2);
    im.add_channel("counts", 7.0f);
    write_exr(dir / "f.exr", im);
    EXPECT_FLOAT_EQ(read_raw_image(dir / "f.exr").at("counts", 1, 1), 7.0f);
    EXPECT_THROW(read_raw_image(dir / "f.exr", "counts", "raw"), Error);
    test::write_text(dir / "bad.png", "not a png");
    EXPECT_THROW(read_raw_image(dir / "bad.png"), Error);
    EXPECT_THROW(read_raw_image(dir / "x.jpg"), Error);
    cv::Mat colour(2, 2, CV_8UC3, cv::Scalar(1, 2, 3));
    cv::imwrite((dir / "c.png").string(), colour);
    EXPECT_THROW(read_raw_image(dir / "c.png"), Error);
}

}  // namespace
}  // namespace tirpol
