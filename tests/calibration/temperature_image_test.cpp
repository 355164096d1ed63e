// `tirpol temperature` and `tirpol flir-temperature`'s library side: counts images through a fitted
// radiometric calibration and through the FLIR model, written as EXRs, and their summaries.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "test_support.h"
#include "tirpol/calibration/flir_image.h"
#include "tirpol/calibration/radiometric.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"

namespace tirpol::calibration {
namespace {

using ::testing::HasSubstr;

constexpr int kW = 4, kH = 2;
constexpr double kGain = 100.0, kOffset = 1000.0;  // counts per W/(m²·sr), counts

// A noiseless linear camera (kGain, kOffset) fitted from blackbodies at 290 K and 320 K.
void write_two_blackbody_calibration(const std::filesystem::path& path, const Band& band) {
    std::vector<BlackbodyFrame> frames;
    for (double t : {290.0, 320.0}) {
        BlackbodyFrame f;
        f.temperature_k = t;
        f.counts.assign(kW * kH, static_cast<float>(kOffset + kGain * band.radiance(t)));
        f.source = "blackbody";
        frames.push_back(f);
    }
    write_radiometric_calibration(path.string(), fit_radiometric(frames, kW, kH, band));
}

void write_counts(const std::filesystem::path& path, double counts) {
    Image image(kW, kH);
    image.add_channel("counts", static_cast<float>(counts));
    write_exr(path, image);
}

// A noiseless linear camera fitted from two blackbodies: a 305 K scene reads 305 K.
TEST(TemperatureImage, LinearCameraReadsTheSceneTemperature) {
    const test::TempDir dir("temperature_image");
    const Band band(8.0, 14.0);
    write_two_blackbody_calibration(dir / "cal.exr", band);
    write_counts(dir / "scene.exr", kOffset + kGain * band.radiance(305.0));
    TemperatureImageOptions o;
    o.image = (dir / "scene.exr").string();
    o.calibration = (dir / "cal.exr").string();
    o.output = (dir / "t.exr").string();
    const TemperatureImageResult r = brightness_temperature_image(o);
    EXPECT_NEAR(r.temperature_k.mean, 305.0, 0.01);
    EXPECT_FALSE(r.warning);  // 305 K lies between the calibration's blackbodies
    const Image out = read_exr(o.output);
    EXPECT_NEAR(out.channel("temperature_k")[3], 305.0, 0.01);
    EXPECT_NEAR(out.channel("radiance")[3], band.radiance(305.0), 1e-3 * band.radiance(305.0));
    EXPECT_EQ(std::get<std::string>(out.attributes().at("calibration")), o.calibration);
    EXPECT_THAT(temperature_image_text(r),
                HasSubstr("brightness temperature: min 305.00 K, mean 305.00 K, max 305.00 K → " +
                          o.output + "\n"));

    // Counts below the offset everywhere: no temperature, nothing written.
    write_counts(dir / "dark.exr", kOffset - 500.0);
    o.image = (dir / "dark.exr").string();
    o.output = (dir / "dark_t.exr").string();
    EXPECT_THROW(brightness_temperature_image(o), Error);
    EXPECT_FALSE(std::filesystem::exists(o.output));
}

TEST(TemperatureImage, ImageOfAnotherSizeIsAnErrorNamingBoth) {
    const test::TempDir dir("temperature_image_size");
    const Band band(8.0, 14.0);
    write_two_blackbody_calibration(dir / "cal.exr", band);
    Image small(2, 2);
    small.add_channel("counts", 2000.0f);
    write_exr(dir / "small.exr", small);
    TemperatureImageOptions o;
    o.image = (dir / "small.exr").string();
    o.calibration = (dir / "cal.exr").string();
    o.output = (dir / "t.exr").string();
    try {
        brightness_temperature_image(o);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), HasSubstr("image is 2×2 but calibration"));
    }
}

// FLIR SC660 constants (G. Tattersall's Thermimage, as in flir_test.cpp): raw 18109 at E = 1, no
// distance, is 296.7743 K; a pixel below −O has no solution.
TEST(FlirImage, Sc660RawImageGivesThePublishedTemperatureAndCountsUnsolvedPixels) {
    const test::TempDir dir("flir_image");
    Image raw(2, 1);
    raw.set_channel("counts", {18109.0f, 100.0f});
    write_exr(dir / "raw.exr", raw);
    FlirImageOptions o;
    o.image = (dir / "raw.exr").string();
    o.output = (dir / "t.exr").string();
    o.planck = {21106.77, 0.012545258, 1501.0, 1.0, -7340.0};
    const FlirImageResult r = flir_temperature_image(o);
    EXPECT_EQ(r.pixels_without_solution, 1u);
    const Image out = read_exr(o.output);
    EXPECT_NEAR(out.channel("temperature_k")[0], 296.7743, 1e-3);
    EXPECT_TRUE(std::isnan(out.channel("temperature_k")[1]));
    EXPECT_EQ(std::get<std::vector<double>>(out.attributes().at("planck_r1_r2_b_f_o")).size(), 5u);
    EXPECT_THAT(flir_image_text(r), HasSubstr("mean 23.62 °C"));
    EXPECT_THAT(flir_image_text(r), HasSubstr("(1 pixel(s) without a solution) → " + o.output));
    o.conditions.emissivity = 0.0;
    EXPECT_THROW(flir_temperature_image(o), Error);
}

}  // namespace
}  // namespace tirpol::calibration
