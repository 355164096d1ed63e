// A microgrid frame read from a 16-bit PNG or an EXR and reduced to Stokes: the counts reach the
// reduction unscaled, the pattern comes from the caller or the EXR header, and conflicts are
// refused.

#include "microgrid_file.h"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "microgrid_scenes.h"
#include "test_support.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"

namespace tirpol::calibration {
namespace {

// Counts of a uniform scene S = (30000, 6000, −9000) through ideal analyzers (integers, so a 16-bit
// PNG holds them exactly).
std::vector<float> uniform_mosaic(int w, int h, const MicrogridPattern& pattern) {
    const std::vector<float> s0(static_cast<std::size_t>(w * h), 30000.0f), s1(s0.size(), 6000.0f),
        s2(s0.size(), -9000.0f);
    return microgrid_from_stokes(s0, s1, s2, w, h, pattern);
}

TEST(MicrogridFile, Reduces16BitPngCountsWithTheGivenPattern) {
    test::TempDir dir;
    const MicrogridPattern sony = MicrogridPattern::sony_imx250mzr();
    const int w = 12, h = 8;
    const std::vector<float> mosaic = uniform_mosaic(w, h, sony);
    cv::Mat png(h, w, CV_16UC1);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            png.at<std::uint16_t>(y, x) =
                static_cast<std::uint16_t>(mosaic[static_cast<std::size_t>(y * w + x)]);
    const auto path = dir / "frame.png";
    ASSERT_TRUE(cv::imwrite(path.string(), png));
    MicrogridReductionOptions options;
    options.method = DemosaicMethod::Bilinear;
    const MicrogridFileReduction reduced = reduce_microgrid_file(path, sony, options);
    const Image& stokes = reduced.stokes;
    EXPECT_EQ(reduced.pattern.angles_deg(), sony.angles_deg());
    EXPECT_EQ(reduced.units, "counts");
    EXPECT_EQ(reduced.unrealizable_pixels, 0);  // DoLP 0.36 everywhere
    EXPECT_EQ(stokes.width(), w);
    EXPECT_NEAR(stokes.at("S0", 5, 3), 30000.0f, 0.05f);
    EXPECT_NEAR(stokes.at("S1", 5, 3), 6000.0f, 0.05f);
    EXPECT_NEAR(stokes.at("S2", 5, 3), -9000.0f, 0.05f);
    EXPECT_EQ(std::get<std::string>(stokes.attributes().at("units")), "counts");
    EXPECT_EQ(std::get<int>(stokes.attributes().at("source_depth_bits")), 16);
    EXPECT_EQ(std::get<std::string>(stokes.attributes().at("demosaic_method")), "bilinear");
    // A PNG records no pattern: without one the file is refused, naming it.
    try {
        reduce_microgrid_file(path, std::nullopt, options);
        FAIL() << "no pattern accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("frame.png: no microgrid pattern given"),
                  std::string::npos)
            << e.what();
    }
}

TEST(MicrogridFile, TakesThePatternFromAnExrHeaderAndRefusesAConflictingOne) {
    test::TempDir dir;
    const MicrogridPattern pattern = MicrogridPattern::parse("0,45,135,90");
    const int w = 8, h = 8;
    Image frame(w, h);
    frame.set_channel("counts", uniform_mosaic(w, h, pattern));
    pattern.write_to(frame.attributes());
    frame.attributes()["units"] = std::string("W/(m^2 sr)");
    const auto path = dir / "frame.exr";
    write_exr(path, frame);
    const MicrogridFileReduction reduced = reduce_microgrid_file(path, std::nullopt, {});
    const Image& stokes = reduced.stokes;
    EXPECT_NEAR(stokes.at("S1", 2, 2), 6000.0f, 0.05f);
    EXPECT_EQ(reduced.units, "W/(m^2 sr)");
    EXPECT_EQ(reduced.pattern.text(), "0,45,135,90");
    EXPECT_EQ(std::get<std::string>(stokes.attributes().at("units")), "W/(m^2 sr)");
    EXPECT_EQ(std::get<std::string>(stokes.attributes().at("microgrid_pattern")), "0,45,135,90");
    EXPECT_THROW(reduce_microgrid_file(path, MicrogridPattern::sony_imx250mzr(), {}), Error);
    EXPECT_THROW(reduce_microgrid_file(path, std::nullopt, {}, "S0"), Error);  // no such channel
}

}  // namespace
}  // namespace tirpol::calibration
