#pragma once
/// \file raster_io.h
/// Reading single-channel raw camera images saved by other tools (FLIR/vendor exports): 16-bit or
/// 8-bit PNG, TIFF (8/16-bit integer or 32-bit float) and OpenEXR, into an Image with one channel.

#include <filesystem>
#include <string>

#include "tirpol/core/image.h"

namespace tirpol {

/// Reads `path` by extension: .exr (the channel `exr_channel` must exist), .png, .tif/.tiff (one
/// channel, integer values kept as is, no scaling) into an Image whose single channel is named
/// `channel_name`. Throws tirpol::Error naming the file for an unreadable file, a colour image or
/// an unsupported extension.
Image read_raw_image(const std::filesystem::path& path, const std::string& channel_name = "counts",
                     const std::string& exr_channel = "counts");

}  // namespace tirpol
