// Regions-of-interest YAML: parsing, rasterisation by hand-counted pixels, and clear errors.

#include "tirpol/report/regions.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>

#include "error_of.h"
#include "test_support.h"
#include "tirpol/core/error.h"

using tirpol::test::error_of;

using namespace tirpol::report;
using ::testing::HasSubstr;

TEST(ReportRegions, ParsesNamedPolygonsAndBackground) {
    tirpol::test::TempDir dir;
    tirpol::test::write_text(dir / "rois.yaml",
                             "background: sky\nregions:\n  - name: panel\n    polygon: [[1, 1], "
                             "[3, 1], [3, 2], [1, 2]]\n"
                             "  - name: sky\n    polygon: [[0, 0], [4, 0], [2, 3]]\n");
    const RegionSet set = load_regions(dir / "rois.yaml");
    ASSERT_EQ(set.regions.size(), 2u);
    EXPECT_EQ(set.regions[0].name, "panel");
    EXPECT_EQ(set.background, "sky");
    EXPECT_TRUE(set.noise_region.empty());
    // Vertices are pixel centres, edges included: columns 1..3 × rows 1..2 = 6 pixels.
    const auto mask = region_mask(set.regions[0], 5, 4);
    EXPECT_EQ(std::count(mask.begin(), mask.end(), 1), 6);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 5; ++x)
            EXPECT_EQ(mask[static_cast<std::size_t>(y * 5 + x)],
                      (x >= 1 && x <= 3 && y >= 1 && y <= 2) ? 1 : 0);
}

TEST(ReportRegions, UnknownKeyIsReportedWithFileLineAndSuggestion) {
    const auto msg = error_of(
        [] { load_regions(tirpol::test::source_dir() / "tests/report/data/rois_typo.yaml"); });
    EXPECT_THAT(msg, HasSubstr("rois_typo.yaml:4"));
    EXPECT_THAT(msg, HasSubstr("polygn"));
    EXPECT_THAT(msg, HasSubstr("polygon"));
}

TEST(ReportRegions, MalformedPolygonsFail) {
    tirpol::test::TempDir dir;
    tirpol::test::write_text(dir / "two.yaml",
                             "regions:\n  - name: a\n    polygon: [[0, 0], [1, 1]]\n");
    EXPECT_THAT(error_of([&] { load_regions(dir / "two.yaml"); }),
                HasSubstr("at least 3 vertices"));
    tirpol::test::write_text(dir / "xyz.yaml",
                             "regions:\n  - name: a\n    polygon: [[0, 0, 1], [1, 1], [2, 0]]\n");
    EXPECT_THAT(error_of([&] { load_regions(dir / "xyz.yaml"); }), HasSubstr("[x, y]"));
    tirpol::test::write_text(dir / "text.yaml",
                             "regions:\n  - name: a\n    polygon: [[0, zero], [1, 1], [2, 0]]\n");
    EXPECT_THAT(error_of([&] { load_regions(dir / "text.yaml"); }), HasSubstr("text.yaml:3"));
    tirpol::test::write_text(
        dir / "bg.yaml",
        "background: skyy\nregions:\n  - name: sky\n    polygon: [[0, 0], [1, 1], [2, 0]]\n");
    const auto msg = error_of([&] { load_regions(dir / "bg.yaml"); });
    EXPECT_THAT(msg, HasSubstr("'skyy' names no region"));
    EXPECT_THAT(msg, HasSubstr("did you mean 'sky'"));
    tirpol::test::write_text(dir / "dup.yaml",
                             "regions:\n  - name: a\n    polygon: [[0, 0], [1, 1], [2, 0]]\n"
                             "  - name: a\n    polygon: [[0, 0], [1, 1], [2, 0]]\n");
    EXPECT_THAT(error_of([&] { load_regions(dir / "dup.yaml"); }),
                HasSubstr("duplicate region name 'a'"));
    tirpol::test::write_text(dir / "syntax.yaml",
                             "regions:\n  - name: a\n    polygon: [[0, 0], [1, 1]\n");
    EXPECT_THAT(error_of([&] { load_regions(dir / "syntax.yaml"); }), HasSubstr("syntax.yaml"));
}

TEST(ReportRegions, EmptyOrOutsideRegionsFailNamingTheRegion) {
    const Region flat{"flat", {{1, 1}, {2, 2}, {3, 3}}, "rois.yaml:3:5: regions[0]"};
    auto msg = error_of([&] { region_mask(flat, 10, 10); });
    EXPECT_THAT(msg, HasSubstr("rois.yaml:3:5"));
    EXPECT_THAT(msg, HasSubstr("'flat' is empty"));
    const Region outside{"far", {{20, 20}, {30, 20}, {30, 30}}, "rois.yaml:5:5: regions[1]"};
    msg = error_of([&] { region_mask(outside, 10, 10); });
    EXPECT_THAT(msg, HasSubstr("'far'"));
    EXPECT_THAT(msg, HasSubstr("outside the 10×10 measured image"));
    // A sliver between pixel centres has area but contains no pixel centre.
    const Region sliver{
        "sliver", {{1.2, 1.2}, {1.8, 1.2}, {1.8, 1.8}}, "rois.yaml:7:5: regions[2]"};
    EXPECT_THAT(error_of([&] { region_mask(sliver, 10, 10); }), HasSubstr("covers no pixel"));
}
