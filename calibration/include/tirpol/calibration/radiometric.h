#pragma once
/// \file radiometric.h
/// Per-pixel radiometric calibration from blackbody frames: counts = offset + gain·L (+ quadratic·L²),
/// where L is the in-band radiance of the blackbody, ∫ R(λ) L_bb(λ, T) dλ in W/(m²·sr) (core's
/// Band). Fitted by linear least squares with the same design matrix for every pixel, so the fit is
/// one small matrix product per pixel.

#include <optional>
#include <string>
#include <vector>

#include "tirpol/calibration/bad_pixels.h"
#include "tirpol/core/image.h"
#include "tirpol/core/radiometry.h"

namespace tirpol::calibration {

/// One averaged blackbody frame: `counts` is the per-pixel mean over `frames` frames and `counts_std`
/// the per-pixel temporal standard deviation (empty if unknown). `source` names it in messages.
struct BlackbodyFrame {
    double temperature_k = 0.0;
    std::vector<float> counts;
    std::vector<float> counts_std;
    int frames = 1;
    std::string source;
};

struct RadiometricOptions {
    bool quadratic = false;  ///< fit counts = o + g·L + q·L² (needs ≥ 3 temperatures)
    /// Counts at or above this level are saturated (e.g. 2^bits − 1); none if unset.
    std::optional<double> saturation_counts;
    /// A frame with more saturated pixels than this fraction is an error, not a bad-pixel class.
    double max_saturated_fraction = 0.001;
    BadPixelThresholds thresholds;
};

/// The camera a calibration was made with, as the session manifest names it. Gains and offsets
/// are per pixel of one detector: applying them to another camera (even of the same size) gives
/// plausible-looking nonsense, so reduction compares this identity with the session's.
struct CalibrationCamera {
    std::string vendor, model, serial, pixel_format;
    int bits_per_pixel = 0;  ///< 0: unknown
    bool known() const { return !serial.empty() || !model.empty(); }
};

/// The result of a radiometric calibration; planes are width × height, row-major.
struct RadiometricCalibration {
    int width = 0, height = 0;
    std::vector<float> gain;          ///< counts per W/(m²·sr)
    std::vector<float> offset;        ///< counts
    std::vector<float> quadratic;     ///< counts per (W/(m²·sr))²; empty for the linear model
    std::vector<float> bad;           ///< BadPixel bit mask (as float)
    std::vector<float> residual_rms;  ///< RMS of the fit residuals, counts
    /// RMS residual divided by the expected noise of a frame mean (counts_std/√frames); ≈ 1 for a
    /// good fit, NaN when counts_std is unknown or there are no degrees of freedom.
    std::vector<float> fit_quality;
    std::vector<double> temperatures_k;
    std::vector<double> radiances_w_m2_sr;
    double band_lo_um = 0.0, band_hi_um = 0.0;
    std::vector<double> rsr_wavelength_um, rsr_response;  ///< empty: flat response
    std::string camera_id;
    CalibrationCamera camera;  ///< unknown in files written before tirpol recorded it
    std::string created_utc;

    /// The band the calibration was made for (with its RSR).
    Band band() const;
    /// Number of pixels with a bad-pixel bit set.
    std::size_t bad_count(std::uint32_t bits = 0xffffffffu) const;
};

/// Fits the per-pixel model to ≥ 2 blackbody frames at distinct temperatures (≥ 3 for the quadratic
/// model). Throws tirpol::Error naming the frame for: fewer temperatures than needed, size mismatch,
/// NaN/inf counts, or too many saturated pixels. Bad pixels are detected as documented in BadPixel.
RadiometricCalibration fit_radiometric(const std::vector<BlackbodyFrame>& frames, int width, int height,
                                       const Band& band, const RadiometricOptions& options = {});

/// Counts → apparent in-band radiance W/(m²·sr) (inverse of the fitted model, the root of the
/// quadratic that continues the linear branch). Bad pixels are replaced (replace_bad_pixels).
std::vector<float> counts_to_radiance(const RadiometricCalibration& cal, const std::vector<float>& counts);

/// Radiance → counts (the forward model), for simulation and tests.
std::vector<float> radiance_to_counts(const RadiometricCalibration& cal, const std::vector<float>& radiance);

/// Field offset update (drift between calibration and collection): from one frame of a blackbody or
/// shutter at `temperature_k`, offset := counts − gain·L(T) − q·L(T)²; gains are kept.
void update_offset(RadiometricCalibration& cal, const BlackbodyFrame& frame);

/// Brightness temperature image (K) from a radiance image, NaN where radiance ≤ 0 or not finite.
std::vector<float> brightness_temperature(const Band& band, const std::vector<float>& radiance);

/// Writes the calibration as EXR: channels gain, offset, [quadratic], bad, residual_rms, fit_quality;
/// attributes tirpol_calibration="radiometric", model, temperatures_k, radiances_w_m2_sr, band_um,
/// rsr_wavelength_um, rsr_response, camera_id, camera_vendor, camera_model, camera_serial,
/// camera_pixel_format, camera_bits_per_pixel, created_utc, units_*, bad_* counts. Atomic.
void write_radiometric_calibration(const std::string& path, const RadiometricCalibration& cal);

/// Reads a calibration EXR written by write_radiometric_calibration; errors name the file and the
/// missing channel or attribute.
RadiometricCalibration read_radiometric_calibration(const std::string& path);

}  // namespace tirpol::calibration
