// Provenance: SHA-256 against the FIPS 180-2 appendix B examples, shell quoting that pastes back,
// and input descriptions with the EXR header attributes.

#include "tirpol/report/provenance.h"

#include <gtest/gtest.h>

#include "test_support.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/error.h"
#include "tirpol/report/regions.h"

using namespace tirpol::report;

TEST(ReportProvenance, Sha256MatchesFips180Examples) {
    // FIPS 180-2, appendix B.1, B.2, B.3; and the empty message (NIST SHA examples).
    EXPECT_EQ(sha256_hex("abc"),
              "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
    EXPECT_EQ(sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
              "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
    EXPECT_EQ(sha256_hex(std::string(1000000, 'a')),
              "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
    EXPECT_EQ(sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
    // 55 and 56 bytes straddle the one-block/two-block padding boundary.
    EXPECT_NE(sha256_hex(std::string(55, 'x')), sha256_hex(std::string(56, 'x')));
}

TEST(ReportProvenance, CommandLineIsQuotedOnlyWhereAShellNeedsIt) {
    const char* argv[] = {"tirpol", "compare", "--measured", "a b.exr",
                          "-o",     "out/r",   "--rois",     "it's.yaml"};
    EXPECT_EQ(quoted_command_line(8, argv),
              "tirpol compare --measured 'a b.exr' -o out/r --rois 'it'\\''s.yaml'");
}

TEST(ReportProvenance, InputFileHasChecksumSizeAndHeaderAttributes) {
    tirpol::test::TempDir dir;
    tirpol::write_file_atomic(dir / "f.txt", "abc");
    tirpol::Image header(1, 1);
    header.attributes()["band_um"] = std::vector<double>{8.0, 14.0};
    header.attributes()["spp"] = 64;
    const InputFile f = describe_input("measured", dir / "f.txt", &header);
    EXPECT_EQ(f.sha256, sha256_hex("abc"));
    EXPECT_EQ(f.size_bytes, 3u);
    ASSERT_EQ(f.attributes.size(), 2u);
    EXPECT_EQ(f.attributes[0], (std::pair<std::string, std::string>{"band_um", "[8, 14]"}));
    EXPECT_EQ(f.attributes[1], (std::pair<std::string, std::string>{"spp", "64"}));
    EXPECT_THROW(describe_input("measured", dir / "missing.exr"), tirpol::Error);
}

TEST(ReportProvenance, RegionsYamlReadsBackToTheSameRegions) {
    RegionSet set;
    set.regions.push_back({"flat black \"paint\"", {{1.5, 2.0}, {10.25, 2.0}, {10.25, 7.0}}, ""});
    set.regions.push_back({"Schnee ❄", {{0, 0}, {3, 0}, {3, 3}, {0, 3}}, ""});
    set.background = "Schnee ❄";
    tirpol::test::TempDir dir;
    tirpol::write_file_atomic(dir / "r.yaml", regions_yaml(set));
    const RegionSet back = load_regions(dir / "r.yaml");
    ASSERT_EQ(back.regions.size(), 2u);
    EXPECT_EQ(back.regions[0].name, set.regions[0].name);
    EXPECT_EQ(back.regions[1].name, set.regions[1].name);
    EXPECT_EQ(back.background, set.background);
    for (std::size_t r = 0; r < 2; ++r)
        for (std::size_t i = 0; i < set.regions[r].polygon.size(); ++i) {
            EXPECT_EQ(back.regions[r].polygon[i].x, set.regions[r].polygon[i].x);
            EXPECT_EQ(back.regions[r].polygon[i].y, set.regions[r].polygon[i].y);
        }
}
