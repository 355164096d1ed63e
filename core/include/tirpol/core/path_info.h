#pragma once
/// \file path_info.h
/// `tirpol info PATH`: what an OpenEXR file holds (size, header attributes, per-channel statistics)
/// or, for a directory, the summary of the capture session in it; JSON and text formats.

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "tirpol/core/image.h"
#include "tirpol/core/session_summary.h"

namespace tirpol {

/// An OpenEXR file's size, header and the statistics of each channel.
struct ImageInfo {
    int width = 0, height = 0;
    Attributes attributes;
    std::vector<std::pair<std::string, ChannelStats>> channels;  ///< in the file's order
};

/// What describe_path found: exactly one of image and session is set.
struct PathInfo {
    std::string path;
    std::optional<ImageInfo> image;
    std::optional<SessionSummary> session;
};

/// A directory is read as a capture session (read_session, summarize_session), anything else as
/// an OpenEXR file. Throws tirpol::Error naming the path when it does not read.
PathInfo describe_path(const std::string& path);

/// The JSON description: for an image file, width, height, attributes and channels (min, mean,
/// max, std, nan_count, inf_count; non-finite statistics as null); for a session, its summary
/// (session_summary_to_json) with "session": the path.
nlohmann::json path_info_json(const PathInfo& info);

/// The text description: a heading, the attributes and a table of channel statistics, or
/// session_summary_text.
std::string path_info_text(const PathInfo& info);

}  // namespace tirpol
