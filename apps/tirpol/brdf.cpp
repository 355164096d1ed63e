// `tirpol brdf`: the Mueller BRDF of a material for one pair of directions.

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "cli.h"
#include "tirpol/core/error.h"
#include "tirpol/core/geometry.h"
#include "tirpol/core/utf8.h"
#include "tirpol/materials/material.h"
#include "tirpol/materials/material_reference.h"

namespace tirpol::cli {

namespace {
struct BrdfArgs {
    std::string material;
    double wavelength_um = 10.0;
    std::vector<double> incident_deg, exitant_deg;
    bool json = false;
};

Vec3 direction(const std::vector<double>& theta_phi_deg, const char* option) {
    const double theta = theta_phi_deg[0], phi = theta_phi_deg[1];
    if (!(theta >= 0.0 && theta <= 90.0) || !std::isfinite(phi))
        usage_error(option, "zenith angle {}° must lie in [0, 90] and the azimuth must be finite",
                    theta);
    const double t = deg_to_rad(theta), p = deg_to_rad(phi);
    return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

void run_brdf(const BrdfArgs& a) {
    const materials::Material m = materials::load_material(materials::material_file(a.material));
    const auto [lo, hi] = m.brdf->valid_wavelength_range_um();
    if (!(a.wavelength_um >= lo && a.wavelength_um <= hi))
        fail("--wavelength-um {}: outside the material's data range {}–{} µm", a.wavelength_um, lo,
             hi);
    const Vec3 wi = direction(a.incident_deg, "--incident-deg"),
               wo = direction(a.exitant_deg, "--exitant-deg");
    const MuellerMatrix f = m.brdf->eval(wi, wo, a.wavelength_um);
    nlohmann::json out;
    out["material"] = m.name;
    out["model"] = m.brdf->model();
    out["wavelength_um"] = a.wavelength_um;
    out["incident_deg"] = a.incident_deg;
    out["exitant_deg"] = a.exitant_deg;
    out["frames"] =
        "incident Stokes in surface_frame(-wi, n), exitant in surface_frame(wo, n): S1 > 0 = s";
    nlohmann::json rows = nlohmann::json::array();
    for (int r = 0; r < 4; ++r) rows.push_back({f(r, 0), f(r, 1), f(r, 2), f(r, 3)});
    out["mueller_brdf_per_sr"] = rows;
    nlohmann::json params = nlohmann::json::object();
    for (const auto& p : m.brdf->parameters(a.wavelength_um))
        params[p.name] = {{"value", p.value}, {"unit", p.unit}};
    out["parameters"] = params;
    out["has_delta"] = m.brdf->has_delta();
    if (a.json) {
        std::printf("%s\n", json_text(out, 2).c_str());
        return;
    }
    std::printf("%s (%s) at %g µm, incident (θ, φ) = (%g°, %g°), exitant (%g°, %g°)\n",
                m.name.c_str(), m.brdf->model().c_str(), a.wavelength_um, a.incident_deg[0],
                a.incident_deg[1], a.exitant_deg[0], a.exitant_deg[1]);
    std::printf(
        "Mueller BRDF in 1/sr (incident Stokes in the s/p frame of -wi, exitant in that of wo):\n");
    for (int r = 0; r < 4; ++r)
        std::printf("  % .6e % .6e % .6e % .6e\n", f(r, 0), f(r, 1), f(r, 2), f(r, 3));
    if (m.brdf->has_delta())
        std::printf(
            "(a smooth surface: its specular reflection is a delta lobe, not part of this finite "
            "BRDF)\n");
    std::printf("parameters:");
    for (const auto& p : m.brdf->parameters(a.wavelength_um))
        std::printf(" %s=%g%s%s", p.name.c_str(), p.value, p.unit.empty() ? "" : " ",
                    p.unit.c_str());
    std::printf("\n");
}

void register_brdf(CLI::App& app) {
    auto args = std::make_shared<BrdfArgs>();
    auto* cmd =
        app.add_subcommand("brdf", "Mueller BRDF of a material for one incident/exitant pair");
    cmd->add_option("material", args->material,
                    "Material YAML file or library name (flat_black_paint; docs/materials.md)")
        ->required();
    cmd->add_option("--wavelength-um", args->wavelength_um, "Wavelength in micrometres")
        ->required();
    cmd->add_option("--incident-deg", args->incident_deg,
                    "Incident zenith and azimuth TH PHI (degrees)")
        ->required()
        ->expected(2);
    cmd->add_option("--exitant-deg", args->exitant_deg,
                    "Exitant zenith and azimuth TH PHI (degrees)")
        ->required()
        ->expected(2);
    cmd->add_flag("--json", args->json, "Print JSON");
    cmd->callback([args] { run_brdf(*args); });
}
}  // namespace

TIRPOL_REGISTER_COMMAND(220, register_brdf);

}  // namespace tirpol::cli
