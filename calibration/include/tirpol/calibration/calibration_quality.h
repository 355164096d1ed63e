#pragma once
/// \file calibration_quality.h
/// What a user needs to trust a radiometric calibration (docs/calibration.md, "Calibration
/// quality"): residuals per blackbody set-point in counts and mK, a warning when a linear model
/// leaves structured residuals, the NEDT map, warnings when a calibration is applied beyond the
/// radiance or FPA-temperature range it was fitted over, and a one-page HTML/PNG summary.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "tirpol/calibration/radiometric.h"

namespace tirpol::calibration {

/// Residual of the fitted model at one calibration frame, over the good pixels.
struct SetPointResidual {
    double temperature_k = 0.0;                  ///< blackbody
    double fpa_temperature_k = 0.0;              ///< camera; NaN when the frame has none
    double mean_counts = 0.0, rms_counts = 0.0;  ///< counts − model
    double mean_mk = 0.0, rms_mk = 0.0;  ///< the same in mK: ÷ (mean responsivity · dL/dT)
    double standard_error_mk = 0.0;      ///< of mean_mk: rms_mk / √pixels
    std::size_t pixels = 0;
};

struct CalibrationQuality {
    std::vector<SetPointResidual> set_points;  ///< in the order of the frames
    std::vector<float> nedt_k;        ///< per pixel, at the set-point nearest 300 K; NaN if unknown
    double nedt_temperature_k = 0.0;  ///< blackbody temperature of that set-point
    double nedt_median_k = 0.0;       ///< over good pixels; NaN when counts_std is unknown
    std::vector<std::string> warnings;
};

/// A linear fit whose mean residual at some set-point exceeds both this and 4 standard errors of
/// that mean is structured (a curved response), not noise.
inline constexpr double kStructuredResidualMk = 10.0;

/// Residuals per set-point, the NEDT map and the structured-residual warning (linear model only,
/// ≥ 3 blackbody temperatures) for `cal` fitted from `frames` (the same frames, same order).
CalibrationQuality assess_calibration(const RadiometricCalibration& cal,
                                      const std::vector<BlackbodyFrame>& frames);

/// Fraction (0..1) of `radiance`'s good, finite pixels outside the calibrated blackbody radiance
/// range (their radiance is extrapolated); 0 when the calibration has no set-points or no good
/// pixel.
double outside_calibrated_range_fraction(const RadiometricCalibration& cal,
                                         const std::vector<float>& radiance);

/// A warning when `radiance` (from counts_to_radiance) holds good pixels outside the calibrated
/// blackbody radiance range, or `fpa_temperature_k` lies outside the calibrated FPA range by more
/// than 0.5 K; names the calibrated range in kelvin. std::nullopt when all is inside.
std::optional<std::string> extrapolation_warning(
    const RadiometricCalibration& cal, const std::vector<float>& radiance,
    std::optional<double> fpa_temperature_k = std::nullopt);

/// Writes DIR/index.html (one page: model, ranges, per-set-point table, bad-pixel counts, NEDT,
/// warnings), DIR/maps.exr (channels nedt_k, bad), DIR/nedt.png, DIR/bad_pixels.png and
/// DIR/residuals.png (mean residual in mK against blackbody temperature). DIR is created.
/// "CAL.summary" next to the calibration file "CAL.exr".
std::string default_summary_dir(const std::string& calibration_path);

void write_calibration_summary(const std::filesystem::path& dir, const RadiometricCalibration& cal,
                               const CalibrationQuality& quality);

}  // namespace tirpol::calibration
