#pragma once
/// \file exr_io.h
/// OpenEXR reading and writing. Every channel is written as 32-bit FLOAT (ZIP compressed);
/// reading converts HALF/UINT channels to float. Writes are atomic (temp file + rename).
///
/// Reading single-channel raw camera images saved by other tools (FLIR/vendor exports): 16-bit PNG,
/// TIFF (16/32-bit integer or 32-bit float) and OpenEXR, into an Image with one channel. 8-bit
/// images are refused: they cannot hold camera counts (a display export or a corrupt header).

#include <filesystem>
#include <string>

#include "tirpol/core/image.h"

namespace tirpol {

/// Writes `image` to `path` atomically. Throws tirpol::Error naming the file on failure (full disk,
/// permissions, ...); an existing file at `path` is untouched on failure.
void write_exr(const std::filesystem::path& path, const Image& image);

/// Reads an EXR. Throws tirpol::Error naming the file for a missing, truncated or corrupt file.
Image read_exr(const std::filesystem::path& path);

/// Reads `path` by extension: .exr (the channel `exr_channel` must exist), .png, .tif/.tiff (one
/// channel, integer values kept as is, no scaling) into an Image whose single channel is named
/// `channel_name`. Throws tirpol::Error naming the file for an unreadable file, a colour or 8-bit
/// image, a declared size beyond limits.h (checked before decoding a PNG) or an unsupported
/// extension.
Image read_raw_image(const std::filesystem::path& path, const std::string& channel_name = "counts",
                     const std::string& exr_channel = "counts");

}  // namespace tirpol
