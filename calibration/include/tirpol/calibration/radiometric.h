#pragma once
/// \file radiometric.h
/// Per-pixel radiometric calibration from blackbody frames: counts = offset + gain·L (+
/// quadratic·L²), where L is the in-band radiance of the blackbody, ∫ R(λ) L_bb(λ, T) dλ in
/// W/(m²·sr) (core's Band). Fitted by linear least squares with the same design matrix for every
/// pixel, so the fit is one small matrix product per pixel.
///
/// For an uncooled camera whose response follows its own focal-plane-array (FPA) temperature, gain
/// and offset can be polynomials in ΔT = T_fpa − T_ref (RadiometricOptions::fpa_degree ≥ 1; the
/// form of Nugent, Shaw & Pust, Opt. Eng. 52(6) 061304, 2013, docs/calibration.md), fitted from
/// blackbody frames taken at several camera temperatures and applied frame by frame from each
/// frame's T_fpa.
///
/// Bad-pixel classes, detection thresholds and the replacement rule. A pixel's class is a bit mask
/// stored as a float channel `bad` in the calibration EXR (0 = good).
///
/// What a user needs to trust a radiometric calibration (docs/calibration.md, "Calibration
/// quality"): residuals per blackbody set-point in counts and mK, a warning when a linear model
/// leaves structured residuals, the NEDT map, warnings when a calibration is applied beyond the
/// radiance or FPA-temperature range it was fitted over, and a one-page HTML/PNG summary.
///
/// `tirpol temperature`: a raw image of counts → radiance and brightness temperature with a
/// radiometric calibration, written as an EXR, and the summary of the result.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "tirpol/core/image.h"
#include "tirpol/core/radiometry.h"

namespace tirpol::calibration {

/// Bits of the bad-pixel mask.
enum BadPixel : std::uint32_t {
    kGood = 0,
    kDead = 1u << 0,       ///< responsivity (gain) below `dead_gain_fraction` × median gain
    kHot = 1u << 1,        ///< offset more than `hot_sigma` robust σ above the median offset
    kNoisy = 1u << 2,      ///< temporal noise above `noisy_factor` × median temporal noise
    kNonLinear = 1u << 3,  ///< fit residual more than `nonlinear_sigma` robust σ above the median
                           ///< and not explained by the pixel's temporal noise (fit quality ≥ 3)
    kSaturated = 1u << 4,  ///< at or above the saturation level in a calibration frame
    /// A microgrid pixel whose fitted analyzer is implausible: diattenuation or axis outside the
    /// limits of MicrogridFlatFieldOptions (a missing or damaged micro-polarizer).
    kBadAnalyzer = 1u << 5,
};

/// Thresholds of the detection (robust σ = 1.4826 × median absolute deviation).
struct BadPixelThresholds {
    double dead_gain_fraction = 0.25;
    double hot_sigma = 10.0;
    double noisy_factor = 3.0;
    double nonlinear_sigma = 10.0;
};

/// Median and robust σ (1.4826·MAD) of the finite values of `values`; {NaN, NaN} if none.
struct RobustStats {
    double median;
    double sigma;
};
RobustStats robust_stats(const std::vector<float>& values);

/// Replaces the values of bad pixels (mask ≠ 0) in `plane` (width × height) by the mean of the
/// good pixels in the 3×3 neighbourhood, widening to 5×5 and 7×7 when none is good; NaN if
/// still none. Replacement reads only good pixels, so the result does not depend on scan order.
void replace_bad_pixels(std::vector<float>& plane, const std::vector<float>& bad_mask, int width,
                        int height);

/// One averaged blackbody frame: `counts` is the per-pixel mean over `frames` frames and
/// `counts_std` the per-pixel temporal standard deviation (empty if unknown). `source` names it in
/// messages.
struct BlackbodyFrame {
    double temperature_k = 0.0;
    std::vector<float> counts;
    std::vector<float> counts_std;
    int frames = 1;
    std::string source;
    std::optional<double> fpa_temperature_k;  ///< camera (FPA) temperature during the frames
};

struct RadiometricOptions {
    bool quadratic = false;  ///< fit counts = o + g·L + q·L² (needs ≥ 3 temperatures)
    /// Counts at or above this level are saturated (e.g. 2^bits − 1); none if unset.
    std::optional<double> saturation_counts;
    /// A frame with more saturated pixels than this fraction is an error, not a bad-pixel class.
    double max_saturated_fraction = 0.001;
    BadPixelThresholds thresholds;
    /// Degree of gain and offset in ΔT_fpa (0: one camera state; 1: Nugent et al. 2013; 2: curved).
    int fpa_degree = 0;
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
    /// FPA dependence: at T_fpa the offset is offset + Σ_a offset_fpa[a−1]·ΔT^a and the gain
    /// gain + Σ_a gain_fpa[a−1]·ΔT^a, ΔT = T_fpa − fpa_reference_k (counts/K^a,
    /// counts/(W/(m²·sr))/K^a). Empty for a calibration at one camera state.
    std::vector<std::vector<float>> offset_fpa, gain_fpa;
    double fpa_reference_k = 0.0;             ///< T_ref, K (mean FPA temperature of the frames)
    double fpa_min_k = 0.0, fpa_max_k = 0.0;  ///< FPA temperatures the calibration frames covered
    std::vector<double>
        fpa_temperatures_k;  ///< per calibration frame (with temperatures_k); may be empty
    /// What a user should know about the fit (model inadequate, drift not modelled, …); not stored.
    std::vector<std::string> warnings;

    /// Degree of the FPA dependence (0: one camera state).
    int fpa_degree() const { return static_cast<int>(offset_fpa.size()); }

    /// The band the calibration was made for (with its RSR).
    Band band() const;
    /// Number of pixels with a bad-pixel bit set.
    std::size_t bad_count(std::uint32_t bits = 0xffffffffu) const;
};

/// Fits the per-pixel model to ≥ 2 blackbody frames at distinct temperatures (≥ 3 for the quadratic
/// model). Throws tirpol::Error naming the frame for: fewer temperatures than needed, size
/// mismatch, NaN/inf counts, too many saturated pixels, or a gain ≤ 0 or not finite for most pixels
/// (the records' temperatures do not belong to their frames; the message names the records whose
/// median counts fall as the temperature rises). Bad pixels are detected as documented in BadPixel.
RadiometricCalibration fit_radiometric(const std::vector<BlackbodyFrame>& frames, int width,
                                       int height, const Band& band,
                                       const RadiometricOptions& options = {});

/// Counts → apparent in-band radiance W/(m²·sr) (inverse of the fitted model, the root of the
/// quadratic that continues the linear branch). Bad pixels are replaced (replace_bad_pixels).
/// `fpa_temperature_k` is the frame's camera temperature, required by an FPA-dependent calibration
/// (tirpol::Error without it) and ignored by a single-state one.
std::vector<float> counts_to_radiance(const RadiometricCalibration& cal,
                                      const std::vector<float>& counts,
                                      std::optional<double> fpa_temperature_k = std::nullopt);

/// The single-state calibration (gain, offset planes) of an FPA-dependent one at
/// `fpa_temperature_k`; a copy of `cal` when it has no FPA dependence. `what` names the frame in
/// the error thrown when the calibration needs an FPA temperature and none is given.
RadiometricCalibration at_fpa_temperature(const RadiometricCalibration& cal,
                                          std::optional<double> fpa_temperature_k,
                                          const std::string& what);

/// Field offset update (drift between calibration and collection): from one frame of a blackbody or
/// shutter at `temperature_k`, offset := counts − gain·L(T) − q·L(T)²; gains are kept. With an FPA
/// dependence the reference-state offset is updated so that the model matches the frame at its
/// T_fpa.
void update_offset(RadiometricCalibration& cal, const BlackbodyFrame& frame);

/// Brightness temperature image (K) from a radiance image, NaN where radiance ≤ 0 or not finite.
std::vector<float> brightness_temperature(const Band& band, const std::vector<float>& radiance);

/// Writes the calibration as EXR (format_version 2): channels gain, offset, [quadratic], bad,
/// residual_rms, fit_quality, [offset_fpa<a>, gain_fpa<a> for a = 1..fpa_degree]; attributes
/// tirpol_calibration="radiometric", format_version, model, temperatures_k, radiances_w_m2_sr,
/// band_um, rsr_wavelength_um, rsr_response, camera_id, camera_vendor, camera_model, camera_serial,
/// camera_pixel_format, camera_bits_per_pixel, created_utc, units_*, bad_* counts, and with an FPA
/// dependence fpa_degree, fpa_reference_k, fpa_min_k, fpa_max_k, fpa_temperatures_k. Atomic.
void write_radiometric_calibration(const std::string& path, const RadiometricCalibration& cal);

/// Reads a calibration EXR written by write_radiometric_calibration (format 1, without
/// format_version, or 2); errors name the file and the missing channel or attribute.
RadiometricCalibration read_radiometric_calibration(const std::string& path);

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

/// The raw image (EXR channel `channel`, 16-bit PNG or TIFF), the calibration EXR and the EXR to
/// write. fpa_temperature_k, when unset, is taken from the image's fpa_temperature_k attribute.
struct TemperatureImageOptions {
    std::string image;
    std::string channel = "counts";
    std::string calibration;
    std::string output;
    std::optional<double> fpa_temperature_k;
    bool force = false;  ///< an existing output may be replaced (OutputGuard)
};

/// What brightness_temperature_image wrote.
struct TemperatureImageResult {
    std::string output;
    ChannelStats temperature_k;          ///< of the temperature_k channel
    std::optional<std::string> warning;  ///< pixels outside the calibrated range (also in the EXR)
};

/// Checks the output against the inputs (OutputGuard: OutputConflict before any work), converts
/// counts → radiance (counts_to_radiance, at the FPA temperature) → brightness
/// temperature and writes `options.output` (channels radiance, temperature_k). Throws
/// tirpol::Error when image and calibration differ in size, or when no pixel gives a finite
/// temperature (nothing is written then).
TemperatureImageResult brightness_temperature_image(const TemperatureImageOptions& options);

/// The warning line, if any, and "brightness temperature: min … K, mean … K, max … K → OUTPUT".
std::string temperature_image_text(const TemperatureImageResult& result);

}  // namespace tirpol::calibration
