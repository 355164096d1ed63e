// `tirpol extract-emissivity`'s library side: which band the extraction uses and the errors when
// the band given disagrees with the input's, when none is known, or when a session has no
// calibration (a usage error of --calibration).

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "test_support.h"
#include "tirpol/calibration/emissivity_extraction.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/limits.h"

namespace tirpol::calibration {
namespace {

using ::testing::HasSubstr;

struct Files {
    test::TempDir dir{"extraction_run"};
    EmissivityExtractionOptions options;
    Files() {
        Image stokes(16, 8);
        for (const char* c : {"S0", "S1", "S2"}) stokes.add_channel(c, 1.0f);
        stokes.attributes()["band_um"] = std::vector<double>{8.0, 14.0};
        write_exr(dir / "stokes.exr", stokes);
        test::write_text(dir / "rois.yaml",
                         "reflector: {rect: [0, 0, 4, 4]}\ntargets:\n"
                         "  - {name: t, rect: [8, 4, 4, 4], view_angle_deg: 30, "
                         "temperature_k: 250}\n");
        options.input = (dir / "stokes.exr").string();
        options.rois = (dir / "rois.yaml").string();
        options.output = (dir / "e.csv").string();
    }
};

std::string error_of(const EmissivityExtractionOptions& o) {
    try {
        extract_emissivity(o);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

TEST(EmissivityExtractionRun, BandGivenMustAgreeWithTheStokesImage) {
    Files f;
    f.options.band_um = std::pair{7.5, 13.0};
    EXPECT_THAT(error_of(f.options), HasSubstr("its band_um (8–14 µm) differs from --band-um"));
    EXPECT_FALSE(std::filesystem::exists(f.options.output));
}

TEST(EmissivityExtractionRun, StokesImageWithoutBandNeedsOne) {
    Files f;
    Image bare(16, 8);
    for (const char* c : {"S0", "S1", "S2"}) bare.add_channel(c, 1.0f);
    write_exr(f.dir / "bare.exr", bare);
    f.options.input = (f.dir / "bare.exr").string();
    EXPECT_THAT(error_of(f.options), HasSubstr("no band_um attribute; give --band-um LO HI"));
}

TEST(EmissivityExtractionRun, SessionWithoutCalibrationIsAnErrorOfTheCalibrationOption) {
    Files f;
    std::filesystem::create_directories(f.dir / "session");
    f.options.input = (f.dir / "session").string();
    try {
        extract_emissivity(f.options);
        FAIL() << "expected an error";
    } catch (const OptionValueError& e) {
        EXPECT_EQ(e.option(), "--calibration");
        EXPECT_THAT(e.what(), HasSubstr("is a session: CAL.exr is needed"));
    }
}

}  // namespace
}  // namespace tirpol::calibration
