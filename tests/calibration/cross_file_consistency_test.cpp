// Files that must agree, tampered one at a time from the synthetic sessions
// (write_synthetic_sessions): each contradiction is an error naming the files and records, never an
// output. Before these checks a 90° frame filed under 0° reduced with S1 negated, swapped blackbody
// temperatures made a calibration with median gain −79 and 19,199 of 19,200 pixels "dead", and a
// 3–5 µm radiometric calibration with an 8–14 µm polarimetric one gave S0 < 0 and DoLP NaN — all
// with exit 0.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "test_support.h"
#include "tirpol/calibration/calibration_chain.h"
#include "tirpol/calibration/session_calibration.h"
#include "tirpol/calibration/synthetic_session.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"

namespace tirpol::calibration {
namespace {

namespace fs = std::filesystem;
using testing::HasSubstr;

const Band kBand(8.0, 14.0);

class CrossFileConsistency : public testing::Test {
protected:
    static void SetUpTestSuite() {
        dir_ = new test::TempDir("tirpol-consistency");
        write_synthetic_sessions(dir_->path(), SyntheticCamera{},
                                 synthetic_panel_scene(64, 48, kBand), kBand);
    }
    static void TearDownTestSuite() { delete dir_; }
    static fs::path root() { return dir_->path(); }
    /// Swaps the blackbody temperatures of records 0 and 3 in `lab`'s manifest (the set-points
    /// typed the wrong way round); returns the manifest as written.
    static nlohmann::json swap_set_points(const fs::path& lab) {
        auto manifest = nlohmann::json::parse(read_file(lab / "session.json"));
        auto& records = manifest["records"];
        std::swap(records[0]["blackbody_temperature_k"], records[3]["blackbody_temperature_k"]);
        write_file_atomic(lab / "session.json", manifest.dump(2));
        return manifest;
    }
    static fs::path copy_session(const test::TempDir& tmp, const std::string& name) {
        fs::copy(root() / name, tmp / name, fs::copy_options::recursive);
        return tmp / name;
    }
    /// Message of the tirpol::Error `f` throws ("" if none).
    template <typename F>
    static std::string error_of(F&& f) {
        try {
            f();
        } catch (const Error& e) {
            return e.what();
        }
        return "";
    }
    static test::TempDir* dir_;
};
test::TempDir* CrossFileConsistency::dir_ = nullptr;

TEST_F(CrossFileConsistency, AFrameFiledUnderAnotherAngleIsRefusedNamingFrameAndManifest) {
    const auto cal = calibrate_radiometric_session(root() / "lab", kBand);
    test::TempDir tmp;
    const fs::path scene = copy_session(tmp, "scene");
    // The frames at 0° and 90° trade names: the manifest still files each under its old angle.
    const fs::path p0 = scene / "frames" / "scene_0.0deg.exr",
                   p90 = scene / "frames" / "scene_90.0deg.exr";
    ASSERT_TRUE(fs::exists(p0) && fs::exists(p90));
    fs::rename(p0, scene / "frames" / "swap.exr");
    fs::rename(p90, p0);
    fs::rename(scene / "frames" / "swap.exr", p90);
    const std::string message = error_of([&] { reduce_session(scene, cal, nullptr); });
    EXPECT_THAT(message, HasSubstr(p0.string()));
    EXPECT_THAT(message, HasSubstr("angle_deg_requested = 90°"));
    EXPECT_THAT(message, HasSubstr((scene / "session.json").string()));
    EXPECT_THAT(message, HasSubstr("angle_deg_requested = 0°"));
    // Untampered, the same session reduces.
    EXPECT_EQ(error_of([&] { reduce_session(root() / "scene", cal, nullptr); }), "");
}

TEST_F(CrossFileConsistency, ABlackbodyTemperatureEditedInTheManifestDisagreesWithItsFrame) {
    test::TempDir tmp;
    const fs::path lab = copy_session(tmp, "lab");
    const nlohmann::json manifest = swap_set_points(lab);
    const auto& records = manifest["records"];
    const std::string message = error_of([&] { calibrate_radiometric_session(lab, kBand); });
    EXPECT_THAT(message, HasSubstr("bb_283.15K.exr"));
    EXPECT_THAT(message, HasSubstr("blackbody_temperature_k = 283.15 K"));
    EXPECT_THAT(message, HasSubstr("blackbody_temperature_k = 328.15 K"));
}

TEST_F(CrossFileConsistency,
       SwappedBlackbodyTemperaturesGiveAnErrorNamingTheRecordsNotACalibration) {
    // The operator typed the two set-points the wrong way round: manifest and headers agree, the
    // counts do not. Counts must rise with the blackbody's temperature (gain > 0).
    test::TempDir tmp;
    const fs::path lab = copy_session(tmp, "lab");
    const nlohmann::json manifest = swap_set_points(lab);
    const auto& records = manifest["records"];
    for (int i : {0, 3}) {
        const fs::path frame = lab / records[i]["file"].get<std::string>();
        Image image = read_exr(frame);
        image.attributes()["blackbody_temperature_k"] =
            records[i]["blackbody_temperature_k"].get<double>();
        write_exr(frame, image);
    }
    const std::string message = error_of([&] { calibrate_radiometric_session(lab, kBand); });
    EXPECT_THAT(message, HasSubstr("gain ≤ 0"));
    EXPECT_THAT(message, HasSubstr("of 3072 pixels"));  // 64×48
    // The records that break the order, by file and by the temperature they claim.
    EXPECT_THAT(message, HasSubstr("bb_328.15K.exr at 283.15 K"));
    EXPECT_THAT(message, HasSubstr("bb_283.15K.exr at 328.15 K"));
    EXPECT_THAT(message, HasSubstr("swapped or mistyped"));
}

TEST_F(CrossFileConsistency, APolarimetricCalibrationOfAnotherBandIsRefusedNamingBothFiles) {
    test::TempDir tmp;
    const auto rad8 = calibrate_radiometric_session(root() / "lab", kBand);
    write_radiometric_calibration((tmp / "cal_8-14.exr").string(), rad8);
    auto pol8 = calibrate_polarimetric_session(root() / "polcal", rad8);
    pol8.radiometric_calibration = (tmp / "cal_8-14.exr").string();
    write_polarimetric_calibration((tmp / "pol_8-14.yaml").string(), pol8);
    EXPECT_THAT(read_file(tmp / "pol_8-14.yaml"), HasSubstr("band_um: [8, 14]"));
    const auto pol_back = read_polarimetric_calibration((tmp / "pol_8-14.yaml").string());
    EXPECT_DOUBLE_EQ(pol_back.band_lo_um, 8.0);
    EXPECT_DOUBLE_EQ(pol_back.band_hi_um, 14.0);
    // Same band: accepted.
    EXPECT_EQ(
        error_of([&] { read_calibration_products(tmp / "cal_8-14.exr", tmp / "pol_8-14.yaml"); }),
        "");

    const auto rad3 = calibrate_radiometric_session(root() / "lab", Band(3.0, 5.0));
    write_radiometric_calibration((tmp / "cal_3-5.exr").string(), rad3);
    const std::string message =
        error_of([&] { read_calibration_products(tmp / "cal_3-5.exr", tmp / "pol_8-14.yaml"); });
    EXPECT_THAT(message, HasSubstr((tmp / "pol_8-14.yaml").string() +
                                   " is a polarimetric calibration for 8–14 µm"));
    EXPECT_THAT(message, HasSubstr((tmp / "cal_3-5.exr").string() + " is for 3–5 µm"));
    // The library path too (Python, the twin): the reduction refuses the pair.
    EXPECT_THAT(error_of([&] { reduce_session(root() / "scene", rad3, &pol_back); }),
                HasSubstr("8–14 µm"));
}

}  // namespace
}  // namespace tirpol::calibration
