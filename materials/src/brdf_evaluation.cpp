#include <fmt/printf.h>

#include <cmath>

#include "tirpol/core/error.h"
#include "tirpol/core/geometry.h"
#include "tirpol/materials/material.h"

namespace tirpol::materials {

Vec3 direction_from_zenith_azimuth_deg(double theta_deg, double phi_deg) {
    if (!(theta_deg >= 0.0 && theta_deg <= 90.0) || !std::isfinite(phi_deg))
        fail("zenith angle {}° must lie in [0, 90] and the azimuth must be finite", theta_deg);
    const double t = deg_to_rad(theta_deg), p = deg_to_rad(phi_deg);
    return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

BrdfEvaluation evaluate_brdf(const BrdfEvaluationOptions& options) {
    const Material m = load_material(material_file(options.material));
    const auto [lo, hi] = m.brdf->valid_wavelength_range_um();
    if (!(options.wavelength_um >= lo && options.wavelength_um <= hi))
        fail("--wavelength-um {}: outside the material's data range {}–{} µm",
             options.wavelength_um, lo, hi);
    const Vec3 wi =
        direction_from_zenith_azimuth_deg(options.incident_deg[0], options.incident_deg[1]);
    const Vec3 wo =
        direction_from_zenith_azimuth_deg(options.exitant_deg[0], options.exitant_deg[1]);
    BrdfEvaluation e;
    e.material = m.name;
    e.model = m.brdf->model();
    e.wavelength_um = options.wavelength_um;
    e.incident_deg = options.incident_deg;
    e.exitant_deg = options.exitant_deg;
    e.mueller_brdf_per_sr = m.brdf->eval(wi, wo, options.wavelength_um);
    e.parameters = m.brdf->parameters(options.wavelength_um);
    e.has_delta = m.brdf->has_delta();
    return e;
}

nlohmann::json brdf_evaluation_json(const BrdfEvaluation& e) {
    const MuellerMatrix& f = e.mueller_brdf_per_sr;
    nlohmann::json out;
    out["material"] = e.material;
    out["model"] = e.model;
    out["wavelength_um"] = e.wavelength_um;
    out["incident_deg"] = e.incident_deg;
    out["exitant_deg"] = e.exitant_deg;
    out["frames"] =
        "incident Stokes in surface_frame(-wi, n), exitant in surface_frame(wo, n): S1 > 0 = s";
    nlohmann::json rows = nlohmann::json::array();
    for (int r = 0; r < 4; ++r) rows.push_back({f(r, 0), f(r, 1), f(r, 2), f(r, 3)});
    out["mueller_brdf_per_sr"] = rows;
    nlohmann::json params = nlohmann::json::object();
    for (const auto& p : e.parameters) params[p.name] = {{"value", p.value}, {"unit", p.unit}};
    out["parameters"] = params;
    out["has_delta"] = e.has_delta;
    return out;
}

std::string brdf_evaluation_text(const BrdfEvaluation& e) {
    const MuellerMatrix& f = e.mueller_brdf_per_sr;
    std::string text = fmt::sprintf(
        "%s (%s) at %g µm, incident (θ, φ) = (%g°, %g°), exitant (%g°, %g°)\n", e.material, e.model,
        e.wavelength_um, e.incident_deg[0], e.incident_deg[1], e.exitant_deg[0], e.exitant_deg[1]);
    text +=
        "Mueller BRDF in 1/sr (incident Stokes in the s/p frame of -wi, exitant in that of wo):\n";
    for (int r = 0; r < 4; ++r)
        text += fmt::sprintf("  % .6e % .6e % .6e % .6e\n", f(r, 0), f(r, 1), f(r, 2), f(r, 3));
    if (e.has_delta)
        text +=
            "(a smooth surface: its specular reflection is a delta lobe, not part of this finite "
            "BRDF)\n";
    text += "parameters:";
    for (const auto& p : e.parameters)
        text += fmt::sprintf(" %s=%g%s%s", p.name, p.value, p.unit.empty() ? "" : " ", p.unit);
    return text + "\n";
}

}  // namespace tirpol::materials
