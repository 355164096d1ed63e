#pragma once
/// \file temperature_image.h
/// `tirpol temperature`: a raw image of counts → radiance and brightness temperature with a
/// radiometric calibration, written as an EXR, and the summary of the result.

#include <optional>
#include <string>

#include "tirpol/core/image.h"

namespace tirpol::calibration {

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
