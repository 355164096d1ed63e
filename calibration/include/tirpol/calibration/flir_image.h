#pragma once
/// \file flir_image.h
/// `tirpol flir-temperature`: a raw FLIR image → an object-temperature EXR with the camera's Planck
/// constants and FLIR's corrections (flir.h), and the one-line summary of the result.

#include <cstddef>
#include <string>

#include "tirpol/calibration/flir.h"
#include "tirpol/core/image.h"

namespace tirpol::calibration {

/// The raw image (EXR channel `channel`, 16-bit PNG or TIFF), the EXR to write, and the model.
struct FlirImageOptions {
    std::string image;
    std::string channel = "counts";
    std::string output;
    FlirPlanck planck;
    FlirConditions conditions;
};

/// What flir_temperature_image wrote.
struct FlirImageResult {
    std::string output;
    ChannelStats temperature_k;               ///< of the temperature_k channel
    std::size_t pixels_without_solution = 0;  ///< NaN: no temperature explains the raw value
};

/// Validates the model (validate_flir), converts every pixel and writes `options.output` with the
/// channel temperature_k and the model in its header. Throws tirpol::Error for bad constants or
/// conditions, or an image that does not read.
FlirImageResult flir_temperature_image(const FlirImageOptions& options);

/// "object temperature: min … °C, mean … °C, max … °C (N pixel(s) without a solution) → OUTPUT".
std::string flir_image_text(const FlirImageResult& result);

}  // namespace tirpol::calibration
