#pragma once
// JSON forms of point records and statistics: statistics.json of a point, the MPI messages from the
// ranks to rank 0, the manifest and results.json (private to the sweep module).

#include <nlohmann/json.hpp>

#include "tirpol/sweep/sweep_run.h"

namespace tirpol::sweep::detail {

nlohmann::json statistics_json(const PointStatistics& statistics);
/// Throws tirpol::Error naming `source` for a malformed document.
PointStatistics statistics_from_json(const nlohmann::json& j, const std::string& source);

/// The point's axis values by parameter name.
nlohmann::json parameters_json(const SweepSpec& spec, const SweepPoint& point);
nlohmann::json record_json(const SweepSpec& spec, const PointRecord& record);
/// Status, error, rank, times and statistics of `j` into a record of `points[j["index"]]`.
PointRecord record_from_json(const nlohmann::json& j, const std::vector<SweepPoint>& points);

}  // namespace tirpol::sweep::detail
