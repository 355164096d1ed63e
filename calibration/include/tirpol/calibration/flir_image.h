#pragma once
/// \file flir_image.h
/// `tirpol flir-temperature`: a raw FLIR image → an object-temperature EXR with the camera's Planck
/// constants and FLIR's corrections (flir.h), and the one-line summary of the result.
///
/// The FLIR radiometric model, an alternative to the per-pixel blackbody calibration for cameras
/// that carry factory constants. Blackbody raw signal of an object at T (kelvin):
///     raw(T) = R1 / (R2·(exp(B/T) − F)) − O,     T(raw) = B / ln(R1/(R2·(raw + O)) + F),
/// and the measurement model with object emissivity E, reflected apparent temperature, atmosphere
/// (transmission τ over the object distance, from FLIR's humidity model) and an external IR window
/// (transmission τ_w, emissivity 1 − τ_w, no reflection), the window at mid-path:
///     raw = E·τ1·τw·τ2·raw(T_obj) + (1 − E)·τ1·τw·τ2·raw(T_refl) + (1 − τ1)·τw·τ2·raw(T_atm)
///         + (1 − τw)·τ2·raw(T_win) + (1 − τ2)·raw(T_atm),      τ1 = τ2 = τ(d/2).
/// Atmospheric transmission (Minkina & Dudzik, "Infrared Thermography: Errors and Uncertainties",
/// Wiley 2009, ch. 2; the constants FLIR cameras store as
/// AtmosphericTrans{X,Alpha1,Alpha2,Beta1,Beta2}):
///     H2O = (RH/100)·exp(1.5587 + 0.06939·t − 0.00027816·t² + 0.00000068455·t³)   (t in °C)
///     τ(d) = X·exp(−√d·(α1 + β1·√H2O)) + (1 − X)·exp(−√d·(α2 + β2·√H2O)).
/// The same equations are used by ExifTool's FLIR documentation and G. Tattersall's Thermimage
/// (raw2temp), whose SC660 constants serve as reference values in the tests.

#include <cstddef>
#include <string>

#include "tirpol/core/image.h"

namespace tirpol::calibration {

/// Camera Planck constants (EXIF PlanckR1, PlanckR2, PlanckB, PlanckF, PlanckO).
struct FlirPlanck {
    double r1 = 0.0, r2 = 1.0, b = 0.0, f = 1.0, o = 0.0;
};

/// FLIR's atmospheric transmission constants; defaults are the published values (X = 1.9,
/// α1 = 0.006569, α2 = 0.01262, β1 = −0.002276, β2 = −0.00667).
struct FlirAtmosphereConstants {
    double x = 1.9, alpha1 = 0.006569, alpha2 = 0.01262, beta1 = -0.002276, beta2 = -0.00667;
};

/// Measurement conditions. Temperatures in kelvin; humidity in percent.
struct FlirConditions {
    double emissivity = 1.0;
    double distance_m = 0.0;
    double reflected_k = 293.15;
    double atmosphere_k = 293.15;
    double humidity_pct = 50.0;
    double window_k = 293.15;
    double window_transmission = 1.0;
    FlirAtmosphereConstants atmosphere;
};

/// Blackbody raw signal of an object at `temperature_k`.
double flir_blackbody_raw(const FlirPlanck& p, double temperature_k);
/// Inverse of flir_blackbody_raw; NaN when the logarithm's argument is not positive.
double flir_blackbody_temperature(const FlirPlanck& p, double raw);
/// Atmospheric transmission over `distance_m` at air temperature `air_k` and humidity
/// `humidity_pct`.
double flir_atmospheric_transmission(double distance_m, double air_k, double humidity_pct,
                                     const FlirAtmosphereConstants& c = {});
/// The raw signal the camera reads for an object at `object_k` under `conditions` (forward model).
double flir_raw_from_temperature(const FlirPlanck& p, double object_k,
                                 const FlirConditions& conditions);
/// Object temperature (K) from a raw signal (inverse model); NaN if no temperature explains it.
double flir_temperature_from_raw(const FlirPlanck& p, double raw, const FlirConditions& conditions);
/// Throws tirpol::Error naming the field if constants or conditions are out of range
/// (E in (0, 1], window transmission in (0, 1], distance ≥ 0, humidity in [0, 100], R1, R2, B > 0).
void validate_flir(const FlirPlanck& p, const FlirConditions& conditions);

/// The raw image (EXR channel `channel`, 16-bit PNG or TIFF), the EXR to write, and the model.
struct FlirImageOptions {
    std::string image;
    std::string channel = "counts";
    std::string output;
    FlirPlanck planck;
    FlirConditions conditions;
    bool force = false;  ///< an existing output may be replaced (OutputGuard)
};

/// What flir_temperature_image wrote.
struct FlirImageResult {
    std::string output;
    ChannelStats temperature_k;               ///< of the temperature_k channel
    std::size_t pixels_without_solution = 0;  ///< NaN: no temperature explains the raw value
};

/// Checks the output against the input (OutputGuard: OutputConflict before any work), validates
/// the model (validate_flir), converts every pixel and writes `options.output` with the
/// channel temperature_k and the model in its header. Throws tirpol::Error for bad constants or
/// conditions, or an image that does not read.
FlirImageResult flir_temperature_image(const FlirImageOptions& options);

/// "object temperature: min … °C, mean … °C, max … °C (N pixel(s) without a solution) → OUTPUT".
std::string flir_image_text(const FlirImageResult& result);

}  // namespace tirpol::calibration
