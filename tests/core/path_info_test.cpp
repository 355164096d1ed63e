// describe_path: what `tirpol info` reports of an EXR file (header, statistics with NaN and inf
// counted and shown as null in JSON) and of a session directory.

#include "tirpol/core/path_info.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "test_support.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"

namespace tirpol {
namespace {

using ::testing::HasSubstr;

TEST(PathInfo, ExrStatisticsCountNonFiniteValuesAndJsonShowsThemAsNull) {
    const test::TempDir dir("path_info");
    Image image(2, 2);
    image.set_channel("S0", {1.0f, 2.0f, 3.0f, 6.0f});
    image.set_channel(
        "bad", {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::quiet_NaN(),
                std::numeric_limits<float>::infinity(), std::numeric_limits<float>::quiet_NaN()});
    image.attributes()["band_um"] = std::vector<double>{8.0, 14.0};
    image.attributes()["source"] = std::string("camera");
    const std::string file = (dir / "a.exr").string();
    write_exr(file, image);

    const PathInfo info = describe_path(file);
    ASSERT_TRUE(info.image);
    EXPECT_FALSE(info.session);
    const nlohmann::json j = path_info_json(info);
    EXPECT_EQ(j["width"], 2);
    EXPECT_EQ(j["channels"]["S0"]["mean"].get<double>(), 3.0);
    EXPECT_EQ(j["channels"]["S0"]["max"].get<double>(), 6.0);
    EXPECT_EQ(j["channels"]["bad"]["nan_count"], 3);
    EXPECT_EQ(j["channels"]["bad"]["inf_count"], 1);
    EXPECT_TRUE(j["channels"]["bad"]["mean"].is_null());
    EXPECT_EQ(j["attributes"]["band_um"], nlohmann::json({8.0, 14.0}));
    const std::string text = path_info_text(info);
    EXPECT_THAT(text, HasSubstr(file + ": 2 × 2, 2 channel(s)\n"));
    EXPECT_THAT(text, HasSubstr("  source                       \"camera\"\n"));
    EXPECT_THAT(text, HasSubstr("  band_um                      [8.0,14.0]\n"));
}

TEST(PathInfo, MissingFileAndNonSessionDirectoryAreErrors) {
    const test::TempDir dir("path_info_missing");
    EXPECT_THROW(describe_path((dir / "none.exr").string()), Error);
    EXPECT_THROW(describe_path(dir.path().string()), Error);  // no session.json
}

}  // namespace
}  // namespace tirpol
