// PNG quicklooks and the progress reporter.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "png_text.h"
#include "test_support.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/error.h"
#include "tirpol/core/log.h"
#include "tirpol/core/quicklook.h"

namespace tirpol {
namespace {

TEST(Quicklook, DivergingRangeIsSymmetricAboutZero) {
    QuicklookOptions o;
    o.colormap = Colormap::Diverging;
    std::vector<float> data(1000);
    for (std::size_t i = 0; i < data.size(); ++i) data[i] = static_cast<float>(i) * 0.01f - 2.0f;
    const auto [lo, hi] = quicklook_range(data, o);
    EXPECT_DOUBLE_EQ(lo, -hi);
    EXPECT_GT(hi, 7.0);
}

// Every Stokes quicklook names its unit, and DoLP's scale starts at 0 (its definition's minimum),
// not at the data's smallest value (a render's DoLP bottomed at 2.35e-06 before).
TEST(Quicklook, ChannelOptionsCarryUnitsAndAZeroBasedDoLP) {
    for (const char* channel : {"S0", "S1", "S2", "S3", "DoLP", "AoP", "temperature_k"})
        EXPECT_FALSE(channel_quicklook_options(channel).units.empty()) << channel;
    EXPECT_EQ(channel_quicklook_options("S0").units, "W/(m²·sr)");
    EXPECT_EQ(channel_quicklook_options("S1", "counts").units, "counts");
    std::vector<float> dolp(1000);
    for (std::size_t i = 0; i < dolp.size(); ++i)
        dolp[i] = 2.35e-6f + 1e-4f * static_cast<float>(i);
    const auto [lo, hi] = quicklook_range(dolp, channel_quicklook_options("DoLP"));
    EXPECT_EQ(lo, 0.0);
    EXPECT_NEAR(hi, dolp[989], 1e-4);  // the robust top (99th percentile) stays
    const auto [aop_lo, aop_hi] = quicklook_range(dolp, channel_quicklook_options("AoP"));
    EXPECT_EQ(aop_lo, 0.0);
    EXPECT_EQ(aop_hi, 180.0);
}

TEST(Quicklook, WritesAPngWithColorbarAndGreyNaN) {
    test::TempDir dir;
    std::vector<float> data(40 * 30, 1.0f);
    data[0] = std::nanf("");
    QuicklookOptions o;
    o.title = "S0";
    o.units = "W/(m²·sr)";
    write_quicklook(dir / "s0.png", data, 40, 30, o);
    const std::string png = read_file(dir / "s0.png");
    ASSERT_GT(png.size(), 24u);
    EXPECT_EQ(png.substr(1, 3), "PNG");
    // IHDR width (big-endian at byte 16): the upscaled image plus the colorbar.
    const auto byte = [&](std::size_t i) {
        return static_cast<unsigned>(static_cast<unsigned char>(png[i]));
    };
    const unsigned width = (byte(16) << 24) | (byte(17) << 16) | (byte(18) << 8) | byte(19);
    EXPECT_GT(width, 40u * 8u);
    EXPECT_EQ(default_colormap("S1"), Colormap::Diverging);
    EXPECT_EQ(default_colormap("AoP"), Colormap::Cyclic);
    EXPECT_EQ(default_colormap("S0"), Colormap::Sequential);
}

TEST(Quicklook, CarriesItsTextChunksWithValidChecksums) {
    test::TempDir dir;
    const std::vector<float> data(8 * 6, 2.0f);
    QuicklookOptions o;
    o.title = "S1";
    o.text = {{"Time", "2026-11-27T05:00:00.000Z"},
              {"tirpol.camera", "sim://uniform?width=8"},
              {"tirpol.units", "W/(m²·sr)"}};  // not ASCII: an iTXt chunk
    write_quicklook(dir / "s1.png", data, 8, 6, o);
    const auto text = test::png_text_chunks(dir / "s1.png");
    EXPECT_EQ(text.size(), 3u);
    EXPECT_EQ(text.at("Time"), "2026-11-27T05:00:00.000Z");
    EXPECT_EQ(text.at("tirpol.camera"), "sim://uniform?width=8");
    EXPECT_EQ(text.at("tirpol.units"), "W/(m²·sr)");
    for (const std::string& bad :
         std::vector<std::string>{"", " lead", "two  spaces", std::string(80, 'k'), "é"}) {
        o.text = {{bad, "x"}};
        EXPECT_THROW(write_quicklook(dir / "bad.png", data, 8, 6, o), Error) << bad;
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "bad.png"));
}

TEST(Progress, NonInteractiveOutputIsPlainLines) {
    std::FILE* f = std::tmpfile();
    {
        ProgressReporter p("render", 10, f, 0);
        for (int i = 0; i < 10; ++i) p.advance();
    }
    std::rewind(f);
    char buf[256] = {};
    const std::size_t n = std::fread(buf, 1, sizeof buf - 1, f);
    std::fclose(f);
    const std::string out(buf, n);
    EXPECT_NE(out.find("render: 10/10 (100%)"), std::string::npos) << out;
    EXPECT_EQ(out.find('\r'), std::string::npos);
}

TEST(Progress, DurationFormatting) {
    EXPECT_EQ(format_duration(12.34), "12.3s");
    EXPECT_EQ(format_duration(185), "3m05s");
    EXPECT_EQ(format_duration(3720), "1h02m");
}

}  // namespace
}  // namespace tirpol
