#pragma once
/// \file utc_time.h
/// Timestamps written into manifests, calibration files and fitted materials.

#include <string>

namespace tirpol {

/// Current UTC time as ISO 8601 with a trailing Z, e.g. "2026-11-22T18:05:00Z".
std::string utc_now_iso8601();

}  // namespace tirpol
