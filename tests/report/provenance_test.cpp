// Provenance: SHA-256 against the FIPS 180-2 appendix B examples, shell quoting that pastes back,
// and input descriptions with the EXR header attributes.

#include "tirpol/report/provenance.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <nlohmann/json.hpp>
#include <regex>

#include "synthetic_pair.h"
#include "test_support.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/report/comparison_report.h"
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

namespace {

// Output of `command` (stdout; stderr to stdout), trailing newline removed.
std::string output_of(const std::string& command, const std::filesystem::path& scratch) {
    const auto out = scratch / "out.txt";
    EXPECT_EQ(std::system((command + " > '" + out.string() + "' 2>&1").c_str()), 0) << command;
    std::string text = tirpol::read_file(out);
    while (!text.empty() && text.back() == '\n') text.pop_back();
    return text;
}

}  // namespace

TEST(ReportProvenance, BuildCommitIsACommitOfThisCheckoutOrNotAGitBuild) {
    const std::string commit = build_commit();
    const auto source = tirpol::test::source_dir();
    tirpol::test::TempDir scratch;
    if (!std::filesystem::exists(source / ".git")) {
        EXPECT_EQ(commit, "not a git build");
        return;
    }
    ASSERT_TRUE(std::regex_match(commit, std::regex("[0-9a-f]{40}(-dirty)?"))) << commit;
    // The configure-time commit exists in this repository.
    EXPECT_EQ(output_of("git -C '" + source.string() + "' cat-file -t " + commit.substr(0, 40),
                        scratch.path()),
              "commit");
}

TEST(ReportProvenance, BuildCommitScriptSaysNotAGitBuildOutsideACheckout) {
    // The same script the build runs (cmake/BuildCommit.cmake), on a copy of sources without git
    // (a tarball): inside another repository as well as outside any.
    tirpol::test::TempDir scratch;
    const auto script = tirpol::test::source_dir() / "cmake" / "BuildCommit.cmake";
    const auto tarball = scratch / "tirpol-0.1.0";
    std::filesystem::create_directories(tarball);
    EXPECT_EQ(
        output_of("cmake -DSOURCE_DIR='" + tarball.string() + "' -P '" + script.string() + "'",
                  scratch.path()),
        "not a git build");
    ASSERT_EQ(std::system(("git init -q '" + scratch.path().string() + "'").c_str()), 0);
    EXPECT_EQ(
        output_of("cmake -DSOURCE_DIR='" + tarball.string() + "' -P '" + script.string() + "'",
                  scratch.path()),
        "not a git build");
    // Its own checkout gives the commit (with -dirty while files differ from it).
    ASSERT_EQ(
        std::system(("git -C '" + tarball.string() + "' init -q && git -C '" + tarball.string() +
                     "' -c user.name=t -c user.email=t@t commit -q --allow-empty -m x")
                        .c_str()),
        0);
    const std::string head =
        output_of("git -C '" + tarball.string() + "' rev-parse HEAD", scratch.path());
    EXPECT_EQ(
        output_of("cmake -DSOURCE_DIR='" + tarball.string() + "' -P '" + script.string() + "'",
                  scratch.path()),
        head);
}

TEST(ReportProvenance, PathsAreMadeRelativeToTheReportFolder) {
    tirpol::test::TempDir dir;
    EXPECT_EQ(path_relative_to(dir / "in" / "m.exr", dir / "out" / "report"),
              std::filesystem::path("../../in/m.exr"));
    EXPECT_EQ(path_relative_to(dir / "report" / "m.exr", dir / "report"),
              std::filesystem::path("m.exr"));
}

TEST(ReportProvenance, TheReportNamesItsInputsRelativeToItsFolderAndItsBuildCommit) {
    tirpol::test::TempDir dir;
    test::SyntheticPairOptions o;
    o.width = 64;
    o.height = 48;
    const auto pair = test::make_synthetic_pair(o);
    const auto measured = dir / "data" / "measured.exr";
    std::filesystem::create_directories(measured.parent_path());
    tirpol::write_exr(measured, pair.measured);
    CompareOptions options;
    options.registration = RegistrationMethod::None;
    options.measured_name = measured.string();  // absolute, as a CLI user may type it
    options.provenance.inputs.push_back(describe_input("measured", measured, &pair.measured));
    const auto result =
        write_comparison_report(pair.measured, pair.simulated, options, dir / "out" / "report");
    const auto json = nlohmann::json::parse(tirpol::read_file(result.json));
    EXPECT_EQ(json["provenance"]["inputs"][0]["path"], "../../data/measured.exr");
    EXPECT_EQ(json["provenance"]["build_commit"], build_commit());
    const std::string html = tirpol::read_file(result.html);
    EXPECT_NE(html.find("<code>../../data/measured.exr</code>"), std::string::npos);
    EXPECT_NE(html.find(build_commit()), std::string::npos);
    EXPECT_EQ(html.find(dir.path().string()), std::string::npos)
        << "an absolute path of the test folder is in the page";
}
