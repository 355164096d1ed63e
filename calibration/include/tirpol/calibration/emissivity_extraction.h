#pragma once
/// \file emissivity_extraction.h
/// Polarized emissivity of targets from a reduced Stokes image (paper eq 17 with τ_p → 1):
///     L_SLAR = (1 − ε)·L_dw + ε·L_BB(T)   ⇒   ε_S0 = (S0 − L_dw)/(L_BB − L_dw),
///     ε_S1 = S1/(L_BB − L_dw),   ε_S2 = S2/(L_BB − L_dw),
/// the downwelled radiance L_dw (taken as unpolarized and uniform) from an IR-reflector region,
/// L_BB from a contact temperature or from an in-scene blackbody at the target's temperature. A
/// real reflector also emits: given its emissivity ε_r and temperature T_r, L_dw = (S0_r −
/// ε_r·L_BB(T_r))/(1 − ε_r). What eq 17 cannot remove is a downwelling that is not uniform: the
/// target's polarized reflection weights the sky differently from the reflector's S0
/// (docs/calibration.md, "Emissivity extraction"). The paper writes eq 17 per analyzer angle for
/// radiances normalised to unit response to unpolarized light; applied to the Stokes components
/// (eqs 14–16 are linear) it gives the expressions above. ε_S1 and ε_S2 are in the image Stokes
/// frame (ARCHITECTURE.md): a sky-facing panel seen obliquely has ε_S1 < 0.
///
/// `tirpol extract-emissivity` from files to a CSV: the polarized emissivity of regions of interest
/// (paper eq 17) from a Stokes EXR, or from a session reduced with its calibration first.
///
/// The mean of an image quantity over a pixel rectangle and the standard error of that mean: the
/// one ROI statistic of emissivity extraction (the region means of paper eq 17) and of the digital
/// twin.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "tirpol/core/config.h"
#include "tirpol/core/error.h"
#include "tirpol/core/image.h"
#include "tirpol/core/radiometry.h"

namespace tirpol::calibration {

/// A pixel rectangle [x, y, width, height] (origin top-left).
struct PixelRect {
    int x = 0, y = 0, width = 0, height = 0;
};

struct RegionMean {
    double mean = 0.0;
    /// Of `mean`: sample standard deviation (n − 1) over √n, pixels treated as independent; 0 for n
    /// = 1.
    double standard_error = 0.0;
    std::size_t n = 0;  ///< finite pixels used
};

/// Mean and standard error of value(x, y) over the pixels of `rect` where it is finite (NaN and ±∞
/// skipped). `rect` must lie inside the image(s) `value` reads. Throws tirpol::Error naming `what`
/// and `quantity` when no value is finite.
template <class Value>
RegionMean region_mean_of(const PixelRect& rect, const std::string& what,
                          const std::string& quantity, Value&& value) {
    double sum = 0.0, sum2 = 0.0;
    std::size_t n = 0;
    for (int y = rect.y; y < rect.y + rect.height; ++y)
        for (int x = rect.x; x < rect.x + rect.width; ++x) {
            const double v = value(x, y);
            if (!std::isfinite(v)) continue;
            sum += v;
            sum2 += v * v;
            ++n;
        }
    if (n == 0)
        fail("{}: no finite {} pixel in the rectangle [{}, {}, {}, {}]", what, quantity, rect.x,
             rect.y, rect.width, rect.height);
    const double count = static_cast<double>(n);
    const double mean = sum / count;
    const double variance =
        n > 1 ? std::max(0.0, (sum2 - count * mean * mean) / (count - 1.0)) : 0.0;
    return {mean, std::sqrt(variance / count), n};
}

/// region_mean_of() of channel `channel` of `image`; throws tirpol::Error naming `what` when `rect`
/// is not inside the image.
RegionMean region_mean(const Image& image, const std::string& channel, const PixelRect& rect,
                       const std::string& what);

struct EmissivityTarget {
    std::string name;
    PixelRect rect;
    double view_angle_deg = 0.0;
    std::optional<double> temperature_k;      ///< contact temperature
    double temperature_std_k = 0.5;           ///< its standard uncertainty
    std::optional<PixelRect> blackbody_rect;  ///< in-scene blackbody at the target temperature
};

/// The IR reflector that measures the downwelling. Its own emission is removed when `emissivity` >
/// 0 (then `temperature_k`, a contact reading, is required); 0 takes the reflector as a perfect
/// mirror of its surroundings, as the paper does.
struct EmissivityReflector {
    PixelRect rect;
    double emissivity = 0.0;              ///< directional emissivity toward the camera, [0, 1)
    double emissivity_std = 0.0;          ///< its standard uncertainty (datasheet)
    std::optional<double> temperature_k;  ///< contact temperature
    double temperature_std_k = 0.5;       ///< its standard uncertainty
    /// From the ROI file's `reflector` mapping: `rect` and the optional `emissivity`,
    /// `emissivity_std`, `temperature_k`, `temperature_std_k`; errors name file, line and field.
    static EmissivityReflector from_config(const ConfigNode& node);
};

struct EmissivityRois {
    EmissivityReflector reflector;
    std::vector<EmissivityTarget> targets;
    /// Reads the ROI YAML (docs/calibration.md): keys `reflector: {rect, emissivity,
    /// emissivity_std, temperature_k, temperature_std_k}` (all but rect optional), `targets:
    /// [{name, rect, view_angle_deg, temperature_k | blackbody_rect, temperature_std_k}]`; errors
    /// name file, line, field.
    static EmissivityRois load(const std::string& path);
};

/// One target's result. `*_std` are standard (1σ) uncertainties: the standard errors of the ROI
/// means (spatial σ/√n) of the target, the reflector and the blackbody region, and the
/// contact-temperature σ through dL/dT, propagated to first order.
struct EmissivityResult {
    std::string name;
    double view_angle_deg = 0.0, temperature_k = 0.0;
    std::size_t pixels = 0;
    double l_dw_w_m2_sr = 0.0;  ///< downwelling radiance the reflector shows (band, W/(m²·sr))
    double l_bb_w_m2_sr = 0.0;  ///< the target's blackbody radiance at its temperature (band)
    double eps_s0 = 0.0, eps_s0_std = 0.0;
    double eps_s1 = 0.0, eps_s1_std = 0.0;
    double eps_s2 = 0.0, eps_s2_std = 0.0;
    /// Physically implausible values (ε_S0 outside [0, 1] beyond limits::kEmissivityTolerance), in
    /// words a person can act on; `fit` refuses such rows.
    std::vector<std::string> warnings;
};

/// The downwelled radiance and its standard error from the reflector's ROI, its own emission
/// removed.
RegionMean downwelled_radiance(const Image& stokes, const EmissivityReflector& reflector,
                               const Band& band);

/// Extracts ε per target. Throws tirpol::Error naming the ROI for a rectangle outside the image or
/// empty, a reflector emissivity outside [0, 1) or without a temperature, no finite pixel, L_BB ≤
/// L_dw (the target's emission must exceed the downwelling) or a non-finite result.
std::vector<EmissivityResult> extract_emissivity(const Image& stokes, const EmissivityRois& rois,
                                                 const Band& band);

/// The emissivity CSV (tirpol/core/emissivity_csv.h): frame `image`, the 1σ uncertainties above
/// (`*_std` columns), wavelength_um empty.
std::string emissivity_csv(const std::vector<EmissivityResult>& results);

/// The input (a Stokes EXR, or a session directory with its calibration), the regions YAML and the
/// CSV to write. band_um, when set, must agree with the band of the input.
struct EmissivityExtractionOptions {
    std::string input;
    std::string rois;
    std::string output;
    std::string calibration;   ///< radiometric calibration EXR (a session input)
    std::string polarimetric;  ///< polarimetric calibration YAML (a session input), or ""
    std::optional<std::pair<double, double>> band_um;
    bool force = false;  ///< an existing output may be replaced (OutputGuard)
};

/// Checks the output against the inputs (OutputGuard: OutputConflict before any work), runs the
/// chain (run_calibration_chain) to the emissivity of each target and writes the CSV
/// (emissivity_csv). A session without a calibration throws OptionValueError for --calibration;
/// a band that disagrees with the calibration's or the EXR's, or an EXR without band_um and no
/// band given, throws tirpol::Error naming both.
std::vector<EmissivityResult> extract_emissivity(const EmissivityExtractionOptions& options);

/// One line per target: name, view angle, ε_S0, ε_S1, ε_S2 with their 2σ.
std::string emissivity_results_text(const std::vector<EmissivityResult>& results);

}  // namespace tirpol::calibration
