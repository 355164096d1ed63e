// What a page receives: counts and calibrated values survive the 16-bit wire format within one
// quantisation step, saturated and dead pixels keep their own codes, and with a calibration the
// display temperature of a blackbody's counts is the blackbody's temperature (Planck round trip
// through calibration's counts_to_radiance and brightness_temperature).

#include "display_frame.h"

#include <gtest/gtest.h>

#include <cmath>

#include "decoded_image.h"
#include "tirpol/core/error.h"
#include "tirpol/core/radiometry.h"

namespace tirpol::live {
namespace {

acquisition::CameraInfo camera_info(int width, int height, int bits) {
    acquisition::CameraInfo info;
    info.uri = "sim://test";
    info.width = width;
    info.height = height;
    info.bits_per_pixel = bits;
    info.pixel_format = "Mono14";
    return info;
}

TEST(DisplayFrame, CountsSurviveTheWireWithinOneStepAndFlagsKeepTheirCodes) {
    const int w = 7, h = 5;
    acquisition::Frame frame;
    frame.width = w;
    frame.height = h;
    frame.frame_id = 65537;
    for (int i = 0; i < w * h; ++i)
        frame.counts.push_back(1000.0f + 37.25f * static_cast<float>(i));
    frame.counts[3] = 16383.0f;  // full scale of a 14-bit ADC: saturated
    frame.counts[4] = 0.0f;      // a readout channel that gives nothing: dead
    const DisplayConverter converter(camera_info(w, h, 14), nullptr, DisplayUnit::Counts);
    ASSERT_EQ(converter.saturation_counts(), 16383.0);

    const auto decoded =
        test::decode_live_image(encode_display_image(converter.frame_image(frame)));
    ASSERT_EQ(decoded.codes.size(), 1u);
    EXPECT_EQ(decoded.header["frame_id"], 65537u);
    EXPECT_EQ(decoded.header["channels"][0]["units"], "counts");
    EXPECT_EQ(decoded.codes[0][3], 65535);
    EXPECT_EQ(decoded.codes[0][4], 1);
    // The range covers the unflagged pixels only (a saturated pixel does not stretch it).
    EXPECT_DOUBLE_EQ(decoded.header["channels"][0]["min"].get<double>(), 1000.0);
    EXPECT_DOUBLE_EQ(decoded.header["channels"][0]["max"].get<double>(),
                     1000.0 + 37.25 * (w * h - 1));
    for (int i = 0; i < w * h; ++i) {
        if (i == 3 || i == 4) continue;
        EXPECT_NEAR(decoded.value(0, static_cast<std::size_t>(i)),
                    frame.counts[static_cast<std::size_t>(i)], 0.5 * decoded.step(0) + 1e-9)
            << "pixel " << i;
    }
}

TEST(DisplayFrame, NaNBecomesNoValueAndAConstantImageStaysDecodable) {
    DisplayImage image;
    image.width = 2;
    image.height = 2;
    image.channels.push_back({"DoLP", "", {0.25f, 0.25f, NAN, 0.25f}, {}});
    const auto d = test::decode_live_image(encode_display_image(image));
    EXPECT_EQ(d.codes[0][2], 0);
    EXPECT_DOUBLE_EQ(d.value(0, 0), 0.25);
}

TEST(DisplayFrame, ChannelOfWrongSizeIsAnErrorNamingIt) {
    DisplayImage image;
    image.width = 4;
    image.height = 4;
    image.channels.push_back({"S1", "counts", std::vector<float>(15, 0.0f), {}});
    try {
        (void)encode_display_image(image);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("S1"), std::string::npos) << e.what();
    }
}

/// A linear calibration of an 8×4 camera in the 8–12 µm band: counts = gain·L + offset, every pixel
/// good except one marked bad.
calibration::RadiometricCalibration linear_calibration(int w, int h, double gain, double offset) {
    calibration::RadiometricCalibration cal;
    cal.width = w;
    cal.height = h;
    const auto n = static_cast<std::size_t>(w * h);
    cal.gain.assign(n, static_cast<float>(gain));
    cal.offset.assign(n, static_cast<float>(offset));
    cal.bad.assign(n, 0.0f);
    cal.bad[5] = 1.0f;
    cal.residual_rms.assign(n, 0.0f);
    cal.fit_quality.assign(n, NAN);
    cal.band_lo_um = 8.0;
    cal.band_hi_um = 12.0;
    return cal;
}

TEST(DisplayFrame, TemperatureOfABlackbodysCountsIsItsTemperature) {
    const int w = 8, h = 4;
    const double gain = 400.0, offset = 2000.0;  // counts per W/(m²·sr), counts
    const auto cal = linear_calibration(w, h, gain, offset);
    const Band band(8.0, 12.0);
    acquisition::Frame frame;
    frame.width = w;
    frame.height = h;
    // A blackbody at 300 K fills the view; the band radiance follows Planck's law (core
    // radiometry).
    frame.counts.assign(static_cast<std::size_t>(w * h),
                        static_cast<float>(gain * band.radiance(300.0) + offset));
    const DisplayConverter kelvin(camera_info(w, h, 16), &cal, DisplayUnit::Temperature);
    EXPECT_EQ(kelvin.units(), "K");
    const auto t = kelvin.convert(frame.counts, std::nullopt);
    for (std::size_t i = 0; i < t.size(); ++i)
        if (i != 5) EXPECT_NEAR(t[i], 300.0, 0.01) << "pixel " << i;  // float counts: ~1e-3 K
    const auto flags = kelvin.flags(frame.counts);
    EXPECT_EQ(flags[5], kPixelDead);  // the calibration's bad pixel is shown as dead
    EXPECT_EQ(flags[0], kPixelOk);

    const DisplayConverter radiance(camera_info(w, h, 16), &cal, DisplayUnit::Radiance);
    EXPECT_NEAR(radiance.convert(frame.counts, std::nullopt)[0], band.radiance(300.0),
                1e-3 * band.radiance(300.0));
}

TEST(DisplayFrame, RadianceWithoutCalibrationOrOfAnotherSizeIsRefused) {
    EXPECT_THROW(DisplayConverter(camera_info(8, 4, 14), nullptr, DisplayUnit::Radiance), Error);
    const auto cal = linear_calibration(8, 4, 1.0, 0.0);
    EXPECT_THROW(DisplayConverter(camera_info(640, 512, 14), &cal, DisplayUnit::Counts), Error);
    EXPECT_THROW(parse_display_unit("kelvin"), Error);
    EXPECT_EQ(parse_display_unit("temperature"), DisplayUnit::Temperature);
}

}  // namespace
}  // namespace tirpol::live
