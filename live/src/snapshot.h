#pragma once
// A snapshot from the live view: the Stokes channels as float EXR with the metadata that says what
// was seen (time, analyzer angles, camera, frame ids) and a PNG quick look per channel carrying
// the same metadata as PNG text chunks. Formats through their owners: core's write_exr and
// write_quicklook.

#include <filesystem>
#include <string>
#include <vector>

#include "tirpol/core/image.h"

namespace tirpol::live {

/// The files one snapshot wrote, as names inside its folder.
struct SnapshotFiles {
    std::string exr;
    std::vector<std::string> pngs;
};

/// The header attributes of `image` as (keyword, text) pairs, prefixed "tirpol." (time_utc as
/// PNG's registered "Creation Time" too); lists of numbers comma-separated, numbers in full
/// precision.
std::vector<std::pair<std::string, std::string>> snapshot_text(const Image& image);

/// Writes `folder`/`stem`.exr (every channel of `image`, 32-bit float, its attributes) and
/// `folder`/`stem`_CHANNEL.png for each channel that is not a standard deviation (channel_quick
/// look_options: units, zero-based DoLP, AoP 0–180). Without `force`, an existing file of those
/// names is refused (tirpol::Error naming it) before anything is written; with it, it is replaced
/// atomically.
SnapshotFiles write_snapshot(const std::filesystem::path& folder, const std::string& stem,
                             const Image& image, const std::string& units, bool force);

}  // namespace tirpol::live
