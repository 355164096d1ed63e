// OpenEXR round trips and the clear errors for bad files.

#include "tirpol/core/exr_io.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "error_of.h"
#include "test_support.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/error.h"

using tirpol::test::error_of;

namespace tirpol {
namespace {

Image stokes_image() {
    Image img(7, 5);
    for (const char* c : {"S0", "S1", "S2", "S3", "DoLP", "AoP"}) {
        auto& p = img.add_channel(c);
        for (std::size_t i = 0; i < p.size(); ++i)
            p[i] = static_cast<float>(i) * 0.5f + static_cast<float>(c[1]);
    }
    img.channel("S1")[3] = std::nanf("");
    img.attributes()["units"] = std::string("W/(m^2 sr)");
    img.attributes()["polarizer_angle_deg"] = 45.0;
    img.attributes()["frames"] = 16;
    img.attributes()["band_um"] = std::vector<double>{8.0, 14.0};
    return img;
}

TEST(Exr, RoundTripKeepsChannelsValuesAndAttributes) {
    test::TempDir dir;
    const Image img = stokes_image();
    write_exr(dir / "s.exr", img);
    const Image back = read_exr(dir / "s.exr");
    EXPECT_EQ(back.width(), 7);
    EXPECT_EQ(back.height(), 5);
    for (const auto& c : img.channel_names()) {
        ASSERT_TRUE(back.has_channel(c)) << c;
        for (std::size_t i = 0; i < img.pixel_count(); ++i) {
            const float a = img.channel(c)[i], b = back.channel(c)[i];
            if (std::isnan(a))
                EXPECT_TRUE(std::isnan(b));
            else
                EXPECT_EQ(a, b);
        }
    }
    EXPECT_EQ(std::get<std::string>(back.attributes().at("units")), "W/(m^2 sr)");
    EXPECT_EQ(std::get<double>(back.attributes().at("polarizer_angle_deg")), 45.0);
    EXPECT_EQ(std::get<int>(back.attributes().at("frames")), 16);
    EXPECT_EQ(std::get<std::vector<double>>(back.attributes().at("band_um")),
              (std::vector<double>{8.0, 14.0}));
}

TEST(Exr, WriteLeavesNoTemporaryFiles) {
    test::TempDir dir;
    write_exr(dir / "a.exr", stokes_image());
    write_exr(dir / "a.exr", stokes_image());  // overwrite through rename
    int files = 0;
    for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path())) ++files;
    EXPECT_EQ(files, 1);
}

TEST(Exr, MissingFileIsNamed) {
    test::TempDir dir;
    const auto msg = error_of([&] { read_exr(dir / "nope.exr"); });
    EXPECT_NE(msg.find("nope.exr: no such file"), std::string::npos) << msg;
}

TEST(Exr, CorruptFileIsRejectedWithItsName) {
    test::TempDir dir;
    test::write_text(dir / "junk.exr",
                     "this is not an image at all, just text pretending to be one");
    const auto msg = error_of([&] { read_exr(dir / "junk.exr"); });
    EXPECT_NE(msg.find("junk.exr: not an OpenEXR file"), std::string::npos) << msg;
}

TEST(Exr, TruncatedFileIsRejectedNotHalfRead) {
    test::TempDir dir;
    Image big(64, 64);
    auto& p = big.add_channel("counts");
    for (std::size_t i = 0; i < p.size(); ++i) p[i] = static_cast<float>((i * 7919) % 1000);
    write_exr(dir / "full.exr", big);
    const std::string bytes = read_file(dir / "full.exr");
    for (double fraction : {0.9, 0.5}) {
        const auto cut = static_cast<std::size_t>(static_cast<double>(bytes.size()) * fraction);
        test::write_text(dir / "cut.exr", bytes.substr(0, cut));
        const auto msg = error_of([&] { read_exr(dir / "cut.exr"); });
        EXPECT_NE(msg.find("cut.exr"), std::string::npos) << msg;
        EXPECT_TRUE(msg.find("truncated") != std::string::npos ||
                    msg.find("corrupt") != std::string::npos)
            << msg;
    }
}

TEST(Exr, UnwritableDestinationIsAClearError) {
    const auto msg =
        error_of([&] { write_exr("/proc/tirpol-cannot-write/x.exr", stokes_image()); });
    EXPECT_NE(msg.find("x.exr"), std::string::npos) << msg;
}

TEST(Image, MissingChannelErrorListsThosePresent) {
    const Image img = stokes_image();
    const auto msg = error_of([&] { (void)img.channel("counts"); });
    EXPECT_NE(msg.find("no channel 'counts'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("S0"), std::string::npos) << msg;
}

TEST(Image, ChannelStatsCountNaNAndIgnoreIt) {
    const ChannelStats s = channel_stats({1.0f, std::nanf(""), 3.0f, INFINITY});
    EXPECT_EQ(s.nan_count, 1u);
    EXPECT_EQ(s.inf_count, 1u);
    EXPECT_DOUBLE_EQ(s.mean, 2.0);
    EXPECT_DOUBLE_EQ(s.min, 1.0);
    EXPECT_DOUBLE_EQ(s.max, 3.0);
}

}  // namespace
}  // namespace tirpol
