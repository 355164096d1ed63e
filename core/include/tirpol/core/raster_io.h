#pragma once
/// \file raster_io.h
/// Reading single-channel raw camera images saved by other tools (FLIR/vendor exports): 16-bit PNG,
/// TIFF (16/32-bit integer or 32-bit float) and OpenEXR, into an Image with one channel. 8-bit
/// images are refused: they cannot hold camera counts (a display export or a corrupt header).

#include <filesystem>
#include <string>

#include "tirpol/core/image.h"

namespace tirpol {

/// Reads `path` by extension: .exr (the channel `exr_channel` must exist), .png, .tif/.tiff (one
/// channel, integer values kept as is, no scaling) into an Image whose single channel is named
/// `channel_name`. Throws tirpol::Error naming the file for an unreadable file, a colour or 8-bit
/// image, a declared size beyond limits.h (checked before decoding a PNG) or an unsupported
/// extension.
Image read_raw_image(const std::filesystem::path& path, const std::string& channel_name = "counts",
                     const std::string& exr_channel = "counts");

}  // namespace tirpol
