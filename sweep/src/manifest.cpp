#include "manifest.h"

#include "records_json.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/error.h"

namespace tirpol::sweep::detail {

void write_manifest(const std::filesystem::path& path, const SweepSpec& spec,
                    const SweepSummary& summary) {
    nlohmann::json axes = nlohmann::json::array(), points = nlohmann::json::array();
    for (const auto& a : spec.axes)
        axes.push_back({{"parameter", a.parameter}, {"values", a.labels}});
    double seconds = 0.0, render_seconds = 0.0, wait_seconds = 0.0;
    std::size_t messaged = 0;
    for (const auto& r : summary.points) {
        points.push_back(record_json(spec, r));
        if (r.status != "rendered") continue;
        seconds += r.seconds;
        render_seconds += r.render_seconds;
        if (r.rank != 0) wait_seconds += r.wait_seconds, ++messaged;
    }
    const nlohmann::json j = {
        {"sweep", spec.file.string()},
        {"scene", spec.scene.file().string()},
        {"combine", spec.combine == Combine::Grid ? "grid" : "list"},
        {"seed", spec.seed},
        {"axes", axes},
        {"ranks", summary.ranks},
        {"threads_per_rank", summary.threads},
        {"summary",
         {{"points", summary.points.size()},
          {"rendered", summary.rendered},
          {"resumed", summary.resumed},
          {"failed", summary.failed},
          {"wall_seconds", summary.wall_seconds},
          {"mean_point_seconds",
           summary.rendered ? seconds / static_cast<double>(summary.rendered) : 0.0},
          {"mean_render_seconds",
           summary.rendered ? render_seconds / static_cast<double>(summary.rendered) : 0.0},
          // Scheduling overhead: how long a rank other than 0 waited for each assignment.
          {"mean_wait_seconds", messaged ? wait_seconds / static_cast<double>(messaged) : 0.0}}},
        {"points", points}};
    write_file_atomic(path, j.dump(2) + "\n");
}

void check_same_sweep(const std::filesystem::path& path, const SweepSpec& spec,
                      const std::vector<SweepPoint>& points) {
    const auto j = nlohmann::json::parse(read_file(path), nullptr, false);
    if (j.is_discarded() || !j.contains("points") || !j["points"].is_array())
        fail("{}: not a sweep manifest (cannot resume)", path.string());
    const auto& old = j["points"];
    if (old.size() != points.size())
        fail("{}: --resume of a different sweep: the folder holds {} points, this sweep has {}",
             path.string(), old.size(), points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
        const auto params = parameters_json(spec, points[i]);
        if (old[i].value("id", "") != points[i].id ||
            old[i].value("parameters", nlohmann::json()) != params ||
            old[i].value("seed", std::uint64_t{0}) != points[i].seed)
            fail(
                "{}: --resume of a different sweep: point {} was {} with seed {}, is now {} with "
                "seed {}",
                path.string(), points[i].id, old[i].value("parameters", nlohmann::json()).dump(),
                old[i].value("seed", std::uint64_t{0}), params.dump(), points[i].seed);
    }
}

}  // namespace tirpol::sweep::detail
