#include <fmt/format.h>

#include "tirpol/sweep/sweep_run.h"

namespace tirpol::sweep {

const std::vector<std::string>& sweep_output_patterns() {
    static const std::vector<std::string> patterns = {
        "manifest.json", "results.csv", "results.json", "contact_sheet_*.png",
        "points",        "plots",       "tiles",        "animation"};
    return patterns;
}

std::string sweep_summary_text(const SweepSummary& s, const std::string& sweep_name,
                               const std::filesystem::path& out_dir) {
    std::string text = fmt::format(
        "sweep {}: {} points on {} rank(s) × {} thread(s) in {:.1f} s: {} rendered, {} resumed, "
        "{} failed\n",
        sweep_name, s.points.size(), s.ranks, s.threads, s.wall_seconds, s.rendered, s.resumed,
        s.failed);
    for (const auto& p : s.outputs)
        if (p.parent_path() == out_dir) text += fmt::format("  {}\n", p.string());
    for (const auto& r : s.points)
        if (r.status == "failed") text += fmt::format("  FAILED {}: {}\n", r.point.id, r.error);
    return text;
}

}  // namespace tirpol::sweep
