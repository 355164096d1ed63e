// StokesImageHeader (declared in exr_io.h): the on-disk names and types of the header attributes
// modules exchange, in this one place.

#include <cmath>
#include <variant>

#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"

namespace tirpol {

namespace {
constexpr const char* kUnits = "units";
constexpr const char* kBand = "band_um";
constexpr const char* kVarianceDof = "variance_dof";
constexpr const char* kVarianceNote = "variance_note";
constexpr const char* kStdIncludes = "std_includes";
constexpr const char* kCalibrationRange = "calibration_range_k";
constexpr const char* kOutsideRangeFraction = "calibration_outside_range_fraction";
constexpr const char* kAnalyzerAngles = "analyzer_angles_deg";
constexpr const char* kFpaTemperature = "fpa_temperature_k";
constexpr const char* kCameraIntrinsics = "camera_intrinsics_px";
constexpr const char* kCameraDistortion = "camera_distortion";

// The attribute `name` as a T, absent when missing; `what` says what it should be.
template <typename T>
std::optional<T> typed(const Image& image, const std::string& where, const char* name,
                       const char* what) {
    const auto it = image.attributes().find(name);
    if (it == image.attributes().end()) return std::nullopt;
    const T* value = std::get_if<T>(&it->second);
    if (!value) fail("{}: header attribute '{}' should be {}", where, name, what);
    return *value;
}

// Two finite reals lo < hi (above zero where `positive`).
std::optional<std::array<double, 2>> interval(const Image& image, const std::string& where,
                                              const char* name, bool positive) {
    const char* what = positive ? "2 reals 0 < LO < HI" : "2 finite reals LO ≤ HI";
    const auto v = typed<std::vector<double>>(image, where, name, what);
    if (!v) return std::nullopt;
    if (v->size() != 2 || !std::isfinite((*v)[0]) || !std::isfinite((*v)[1]) ||
        (positive ? !((*v)[0] > 0.0 && (*v)[0] < (*v)[1]) : !((*v)[0] <= (*v)[1])))
        fail("{}: header attribute '{}' should be {}, got {} value(s)", where, name, what,
             v->size());
    return std::array<double, 2>{(*v)[0], (*v)[1]};
}

std::optional<std::array<double, 4>> intrinsics(const Image& image, const std::string& where) {
    const char* what = "4 reals fx fy cx cy";
    const auto v = typed<std::vector<double>>(image, where, kCameraIntrinsics, what);
    if (!v) return std::nullopt;
    if (v->size() != 4)
        fail("{}: header attribute '{}' should be {}, got {} value(s)", where, kCameraIntrinsics,
             what, v->size());
    return std::array<double, 4>{(*v)[0], (*v)[1], (*v)[2], (*v)[3]};
}

std::optional<CalibrationRangeAttribute> calibration_range(const Image& image,
                                                           const std::string& where) {
    const auto range = interval(image, where, kCalibrationRange, false);
    const auto fraction = typed<double>(image, where, kOutsideRangeFraction, "a real in [0, 1]");
    if (!range && !fraction) return std::nullopt;
    if (!range || !fraction)
        fail("{}: header attributes '{}' and '{}' come together; only '{}' is present", where,
             kCalibrationRange, kOutsideRangeFraction,
             range ? kCalibrationRange : kOutsideRangeFraction);
    if (!(*fraction >= 0.0 && *fraction <= 1.0))
        fail("{}: header attribute '{}' should be a real in [0, 1], got {}", where,
             kOutsideRangeFraction, *fraction);
    return CalibrationRangeAttribute{*range, *fraction};
}
}  // namespace

StokesImageHeader read_stokes_image_header(const Image& image, const std::string& where) {
    StokesImageHeader h;
    h.units = typed<std::string>(image, where, kUnits, "text");
    h.band_um = interval(image, where, kBand, true);
    h.variance_dof = typed<int>(image, where, kVarianceDof, "an integer");
    h.variance_note = typed<std::string>(image, where, kVarianceNote, "text");
    h.std_includes = typed<std::string>(image, where, kStdIncludes, "text");
    h.calibration_range = calibration_range(image, where);
    h.analyzer_angles_deg =
        typed<std::vector<double>>(image, where, kAnalyzerAngles, "a list of reals");
    h.fpa_temperature_k = typed<double>(image, where, kFpaTemperature, "a real");
    h.camera_intrinsics_px = intrinsics(image, where);
    h.camera_distortion =
        typed<std::vector<double>>(image, where, kCameraDistortion, "a list of reals");
    return h;
}

void write_stokes_image_header(Image& image, const StokesImageHeader& h) {
    Attributes& a = image.attributes();
    if (h.units) a[kUnits] = *h.units;
    if (h.band_um) a[kBand] = std::vector<double>{(*h.band_um)[0], (*h.band_um)[1]};
    if (h.variance_dof) a[kVarianceDof] = *h.variance_dof;
    if (h.variance_note) a[kVarianceNote] = *h.variance_note;
    if (h.std_includes) a[kStdIncludes] = *h.std_includes;
    if (h.calibration_range) {
        const auto& [range, fraction] = *h.calibration_range;
        a[kCalibrationRange] = std::vector<double>{range[0], range[1]};
        a[kOutsideRangeFraction] = fraction;
    }
    if (h.analyzer_angles_deg) a[kAnalyzerAngles] = *h.analyzer_angles_deg;
    if (h.fpa_temperature_k) a[kFpaTemperature] = *h.fpa_temperature_k;
    if (const auto& k = h.camera_intrinsics_px)
        a[kCameraIntrinsics] = std::vector<double>(k->begin(), k->end());
    if (h.camera_distortion) a[kCameraDistortion] = *h.camera_distortion;
}

}  // namespace tirpol
