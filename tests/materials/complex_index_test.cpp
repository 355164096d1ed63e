// Complex-index tables: the refractiveindex.info YAML layout, CSV, interpolation and clear errors.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "test_support.h"
#include "tirpol/core/error.h"
#include "tirpol/materials/fresnel.h"

namespace tirpol::materials {
namespace {

using ::testing::HasSubstr;

TEST(ComplexIndex, ReadsRefractiveIndexInfoTabulatedNk) {
    test::TempDir dir;
    test::write_text(dir / "x.yml", R"(REFERENCES: "test"
DATA:
  - type: tabulated nk
    data: |
        8.0 1.2 0.1
        10.0 1.4 0.3
)");
    const auto t = RefractiveIndexTable::load(dir / "x.yml");
    EXPECT_NEAR(t.at(9.0).n, 1.3, 1e-12);  // linear interpolation
    EXPECT_NEAR(t.at(9.0).k, 0.2, 1e-12);
    EXPECT_NEAR(t.at(8.0).n, 1.2, 1e-12);
    try {
        t.at(12.0);
        FAIL() << "expected an error outside the table";
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), HasSubstr("x.yml"));
        EXPECT_THAT(e.what(), HasSubstr("12"));
        EXPECT_THAT(e.what(), HasSubstr("8–10"));
    }
    EXPECT_NEAR(t.at_clamped(12.0).n, 1.4, 1e-12);
}

TEST(ComplexIndex, ReadsSeparateNAndKTables) {
    test::TempDir dir;
    test::write_text(dir / "x.yml", R"(DATA:
  - type: tabulated n
    data: |
        8 1.2
        9 1.3
        10 1.4
  - type: tabulated k
    data: |
        7 0.0
        11 0.4
)");
    const auto t = RefractiveIndexTable::load(dir / "x.yml");
    EXPECT_NEAR(t.at(9.0).n, 1.3, 1e-12);
    EXPECT_NEAR(t.at(9.0).k, 0.2, 1e-12);
}

TEST(ComplexIndex, ReadsCsvAndRejectsBadRows) {
    test::TempDir dir;
    test::write_text(dir / "x.csv", "# comment\nwavelength_um,k,n\n8,0.1,1.2\n10,0.3,1.4\n");
    EXPECT_NEAR(RefractiveIndexTable::load(dir / "x.csv").at(9.0).k, 0.2, 1e-12);
    test::write_text(dir / "bad.csv", "wavelength_um,n,k\n8,1.2,0.1\n10,abc,0.3\n");
    try {
        RefractiveIndexTable::load(dir / "bad.csv");
        FAIL();
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), HasSubstr("bad.csv:3"));
        EXPECT_THAT(e.what(), HasSubstr("abc"));
    }
    test::write_text(dir / "neg.csv", "wavelength_um,n,k\n8,1.2,-0.1\n10,1.3,0.3\n");
    EXPECT_THROW(RefractiveIndexTable::load(dir / "neg.csv"), Error);  // k < 0 would amplify
    test::write_text(dir / "order.csv", "wavelength_um,n,k\n10,1.2,0.1\n8,1.3,0.3\n");
    EXPECT_THROW(RefractiveIndexTable::load(dir / "order.csv"), Error);
}

TEST(ComplexIndex, ConstantIsValidEverywhere) {
    const auto t = RefractiveIndexTable::constant({1.5, 0.01});
    EXPECT_TRUE(t.covers(0.1, 1000.0));
    EXPECT_NEAR(t.at(3.0).n, 1.5, 0.0);
    EXPECT_THROW(RefractiveIndexTable::constant({-1.0, 0.0}), Error);
}

// The library's data files are refractiveindex.info excerpts: Hale & Querry (1973) water at 10 µm
// is n = 1.218, k = 0.0508 (their Table 1).
TEST(ComplexIndex, LibraryWaterMatchesHaleQuerry) {
    const auto t = RefractiveIndexTable::load(test::source_dir() /
                                              "config/materials/data/water_hale_querry_1973.yml");
    EXPECT_NEAR(t.at(10.0).n, 1.218, 1e-12);
    EXPECT_NEAR(t.at(10.0).k, 0.0508, 1e-12);
}

}  // namespace
}  // namespace tirpol::materials
