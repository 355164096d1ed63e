// Text summary of a digital-twin run, shared by the demo step and the integration test.

#include <fmt/printf.h>

#include <cmath>

#include "twin.h"

namespace tirpol::cli::twin {

std::string twin_summary(const TwinResult& r) {
    std::string out;
    out += fmt::sprintf("  camera: %s\n", r.camera_transport.c_str());
    out += fmt::sprintf("  stage: %s\n", r.stage_description.c_str());
    out += fmt::sprintf("  sessions:");
    for (const auto& s : r.sessions) out += fmt::sprintf(" %s", s.filename().c_str());
    out += fmt::sprintf(" (in %s)\n", r.sessions.front().parent_path().c_str());
    const auto& t = r.target_stokes;
    out += fmt::sprintf("  flat black paint, view 0 ROI mean, measured vs truth render [W/(m²·sr)]:\n");
    for (int c = 0; c < 3; ++c)
        out += fmt::sprintf("    S%d %9.4f vs %9.4f   (diff %+.4f, σ %.4f of which temporal %.4f, %.1fσ)\n", c,
                            t.measured[c], t.truth[c], t.measured[c] - t.truth[c], t.sigma[c], t.sigma_temporal[c],
                            std::abs(t.measured[c] - t.truth[c]) / t.sigma[c]);
    out += fmt::sprintf("  polarized emissivity (plane-of-emission frame), extracted vs true paint:\n");
    for (const auto& e : r.emissivity)
        out += fmt::sprintf("    θ %5.1f°: ε_S0 %.4f ± %.4f (true %.4f)   ε_S1 %+.4f ± %.4f (true %+.4f)\n",
                            e.view_angle_deg, e.eps_s0, e.eps_s0_sigma, e.true_s0, e.eps_s1, e.eps_s1_sigma, e.true_s1);
    out += fmt::sprintf("  fit (χ²/dof %.2f):\n", r.reduced_chi2);
    for (const auto& p : r.parameters) {
        if (p.fixed) continue;
        out += fmt::sprintf("    %-6s true %.4f  recovered %.4f ± %.4f  (%.1fσ)\n", p.name.c_str(), p.truth, p.fitted,
                            p.sigma, std::abs(p.fitted - p.truth) / p.sigma);
    }
    out += fmt::sprintf("    fixed:");
    for (const auto& p : r.parameters)
        if (p.fixed) out += fmt::sprintf(" %s=%g", p.name.c_str(), p.fitted);
    out += fmt::sprintf(
        "\n  Stokes agreement per region (measured vs fitted render; |z|>2 fraction of S0, S1, S2; 4.6%% expected from "
        "noise):\n");
    for (const auto& g : r.regions)
        out += fmt::sprintf("    %-24s %5zu px  |z|>2 S0 %5.1f%%  S1 %5.1f%%  S2 %5.1f%%  %s\n", g.name.c_str(), g.pixels,
                            100.0 * g.z_above_2[0], 100.0 * g.z_above_2[1], 100.0 * g.z_above_2[2],
                            report::to_string(g.verdict).c_str());
    out += fmt::sprintf("  times:");
    for (const auto& [k, s] : r.seconds) out += fmt::sprintf(" %s %.1f s;", k.c_str(), s);
    out += fmt::sprintf("\n  report: %s\n", r.report_html.c_str());
    return out;
}

}  // namespace tirpol::cli::twin
