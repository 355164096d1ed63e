// Text summary of a digital-twin run, shared by the demo step and the integration test.

#include <fmt/printf.h>

#include <algorithm>
#include <cmath>

#include "tirpol/twin/twin.h"

namespace tirpol::twin {

namespace {

std::string camera_geometry_summary(const CameraGeometryRecovery& c) {
    std::string out = fmt::sprintf(
        "  camera geometry, true vs recovered (lens from %d of %d board frames, RMS %.3f px; pose "
        "from %d panel "
        "corners):\n   ",
        c.lens.views, c.board_frames, c.lens.rms_px, c.control_points);
    const double truth[] = {c.true_lens.fx, c.true_lens.fy, c.true_lens.cx, c.true_lens.cy};
    const double recovered[] = {c.lens.fx, c.lens.fy, c.lens.cx, c.lens.cy};
    for (std::size_t i = 0; i < 4; ++i)
        out += fmt::sprintf(" %s %.2f vs %.2f (%+.2f %%);", c.lens_parameter_names[i].c_str(),
                            truth[i], recovered[i], 100.0 * (recovered[i] / truth[i] - 1.0));
    out += "\n   ";
    for (std::size_t i = 0; i < c.lens.distortion.size(); ++i) {
        const double t = i < c.true_lens.distortion.size() ? c.true_lens.distortion[i] : 0.0;
        out += fmt::sprintf(" %s %+.4f vs %+.4f ± %.4f;", c.lens_parameter_names[4 + i].c_str(), t,
                            c.lens.distortion[i], c.lens.std_dev[4 + i]);
    }
    out += fmt::sprintf(
        "\n    pose: the nominal one is off by %.3f° and %.4f m; the recovered one by %.4f° and "
        "%.4f m\n",
        c.nominal_rotation_error_deg, c.nominal_position_error_m, c.rotation_error_deg,
        c.position_error_m);
    return out;
}

}  // namespace

std::string paint_fit_comparison(const TwinResult& r) {
    const TwinRenderFit& f = r.render_fit;
    std::string out = fmt::sprintf(
        "  paint, eq 17 route (3 emissivity samples) vs fit through the renderer (target Stokes in "
        "%zu views), 1σ:\n",
        r.emissivity.size());
    for (const auto& p : r.parameters) {
        if (p.fixed) continue;
        const auto q = std::find_if(f.parameters.begin(), f.parameters.end(),
                                    [&](const TwinParameter& t) { return t.name == p.name; });
        out += fmt::sprintf("    %-6s true %.4f | eq 17 %.4f ± %.4f (%.1fσ, %+.1f %%)",
                            p.name.c_str(), p.truth, p.fitted, p.std_uncertainty,
                            std::abs(p.fitted - p.truth) / p.std_uncertainty,
                            100.0 * (p.fitted / p.truth - 1.0));
        if (q != f.parameters.end())
            out += fmt::sprintf(" | renderer %.4f ± %.4f (%.1fσ, %+.1f %%)", q->fitted,
                                q->std_uncertainty,
                                std::abs(q->fitted - q->truth) / q->std_uncertainty,
                                100.0 * (q->fitted / q->truth - 1.0));
        out += "\n";
    }
    out += fmt::sprintf(
        "    χ²/dof      | eq 17 %.2f (dof %d) | renderer %.2f (dof %d), %d renders%s\n",
        r.reduced_chi2, r.dof, f.reduced_chi2, f.dof, f.renders, f.usable ? "" : ", NOT CONVERGED");
    for (const auto& w : f.warnings) out += "    renderer fit warning: " + w + "\n";
    return out;
}

std::string twin_summary(const TwinResult& r) {
    std::string out;
    out += fmt::sprintf("  camera: %s\n", r.camera_transport.c_str());
    out += fmt::sprintf("  stage: %s\n", r.stage_description.c_str());
    out += fmt::sprintf("  sessions:");
    for (const auto& s : r.sessions) out += fmt::sprintf(" %s", s.filename().c_str());
    out += fmt::sprintf(" (in %s)\n", r.sessions.front().parent_path().c_str());
    out += camera_geometry_summary(r.camera);
    const auto& t = r.target_stokes;
    out += fmt::sprintf(
        "  flat black paint, view 0 ROI mean, measured vs truth render [W/(m²·sr)]:\n");
    for (int c = 0; c < 3; ++c)
        out += fmt::sprintf(
            "    S%d %9.4f vs %9.4f   (diff %+.4f, σ %.4f of which temporal %.4f, %.1fσ)\n", c,
            t.measured[c], t.truth[c], t.measured[c] - t.truth[c], t.std_error[c],
            t.std_error_temporal[c], std::abs(t.measured[c] - t.truth[c]) / t.std_error[c]);
    out += fmt::sprintf(
        "  polarized emissivity (plane-of-emission frame): measured | eq 17 on the truth render | "
        "true paint\n");
    for (const auto& e : r.emissivity)
        out += fmt::sprintf(
            "    θ %5.1f°: ε_S0 %.4f ± %.4f | %.4f | %.4f   ε_S1 %+.4f ± %.4f | %+.4f | %+.4f\n",
            e.view_angle_deg, e.eps_s0, e.eps_s0_std, e.method_s0, e.true_s0, e.eps_s1,
            e.eps_s1_std, e.method_s1, e.true_s1);
    out += fmt::sprintf("  fit (χ²/dof %.2f):\n", r.reduced_chi2);
    for (const auto& p : r.parameters) {
        if (p.fixed) continue;
        out += fmt::sprintf("    %-6s true %.4f  recovered %.4f ± %.4f  (%.1fσ)\n", p.name.c_str(),
                            p.truth, p.fitted, p.std_uncertainty,
                            std::abs(p.fitted - p.truth) / p.std_uncertainty);
    }
    out += fmt::sprintf("    fixed:");
    for (const auto& p : r.parameters)
        if (p.fixed) out += fmt::sprintf(" %s=%g", p.name.c_str(), p.fitted);
    out += "\n" + paint_fit_comparison(r);
    out += fmt::sprintf(
        "  comparison registration: %s, residual misalignment %.3f px (%s)",
        report::to_string(r.registration.method).c_str(),
        std::hypot(r.registration.residual_shift_px[0], r.registration.residual_shift_px[1]),
        r.registration.note.c_str());
    const double alpha = r.regions.empty() ? 0.0 : r.regions.front().quantities[0].mean.false_alarm;
    const double power = r.regions.empty() ? 0.0 : r.regions.front().quantities[0].mean.power;
    out += fmt::sprintf(
        "\n  Stokes agreement per region (measured vs fitted render): S0, S1, S2 region-mean t = "
        "difference/σ_mean and, "
        "in brackets, the smallest bias detected at %.1f%% false alarm per quantity and %.0f%% "
        "power [W/(m²·sr)]; "
        "σ-high/σ-low: per-pixel σ diagnostic\n",
        100.0 * alpha, 100.0 * power);
    for (const auto& g : r.regions) {
        out += fmt::sprintf("    %-24s %5zu px", g.name.c_str(), g.pixels);
        for (int k = 0; k < 3; ++k) {
            const auto& q = g.quantities[k];
            const char* sigma = q.sigma.verdict == report::SigmaCheck::Overestimated    ? " σ-high"
                                : q.sigma.verdict == report::SigmaCheck::Underestimated ? " σ-low"
                                                                                        : "";
            out +=
                fmt::sprintf("  S%d %+5.1f (%.2g)%s", k, q.mean.t, q.mean.detectable_bias, sigma);
        }
        out += fmt::sprintf("  %s\n", report::to_string(g.verdict).c_str());
    }
    out += fmt::sprintf("  blackbody set-points (from the truth renders' radiances): radiometric");
    for (double k : r.blackbody.radiometric_k) out += fmt::sprintf(" %.1f", k);
    out += fmt::sprintf(" K (detector radiance %.2f–%.2f W/(m²·sr)); polarimetric",
                        r.blackbody.detector_radiance_min, r.blackbody.detector_radiance_max);
    for (double k : r.blackbody.polarimetric_k) out += fmt::sprintf(" %.1f", k);
    out += fmt::sprintf(
        " K (scene S0 %.2f–%.2f W/(m²·sr)); %.1f%% of view 0's pixels outside the calibrated "
        "range%s%s\n",
        r.blackbody.scene_s0_min, r.blackbody.scene_s0_max, 100.0 * r.calibration_outside_fraction,
        r.blackbody.limitation.empty() ? "" : ": ", r.blackbody.limitation.c_str());
    out += "  report summary: " + r.report_summary + "\n";
    out += fmt::sprintf("  times:");
    for (const auto& [k, s] : r.seconds) out += fmt::sprintf(" %s %.1f s;", k.c_str(), s);
    out += fmt::sprintf("\n  report: %s\n", r.report_html.c_str());
    return out;
}

}  // namespace tirpol::twin
