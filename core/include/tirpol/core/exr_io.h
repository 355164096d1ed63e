#pragma once
/// \file exr_io.h
/// OpenEXR reading and writing. Every channel is written as 32-bit FLOAT (ZIP compressed);
/// reading converts HALF/UINT channels to float. Writes are atomic (temp file + rename).

#include <filesystem>

#include "tirpol/core/image.h"

namespace tirpol {

/// Writes `image` to `path` atomically. Throws tirpol::Error naming the file on failure (full disk,
/// permissions, ...); an existing file at `path` is untouched on failure.
void write_exr(const std::filesystem::path& path, const Image& image);

/// Reads an EXR. Throws tirpol::Error naming the file for a missing, truncated or corrupt file.
Image read_exr(const std::filesystem::path& path);

}  // namespace tirpol
