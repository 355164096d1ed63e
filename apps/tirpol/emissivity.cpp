// `tirpol emissivity`: polarized directional emissivity of a material versus emission angle, at one
// wavelength or averaged over a band (Planck × RSR weighted), as a table, CSV, JSON and a Fig.
// 1-style plot.

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <optional>

#include "cli.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/error.h"
#include "tirpol/core/radiometry.h"
#include "tirpol/core/utf8.h"
#include "tirpol/materials/emissivity_curve.h"
#include "tirpol/materials/material.h"
#include "tirpol/materials/material_reference.h"

namespace tirpol::cli {

namespace {
struct EmissivityArgs {
    std::string material;
    std::optional<double> wavelength_um;
    std::vector<double> band_um;
    std::string rsr;
    std::string angles;
    double temperature_k = 300.0;
    std::string csv, plot;
    bool json = false;
    bool force = false;
};

void run_emissivity(const EmissivityArgs& a) {
    OutputGuard()
        .input(a.material, "MATERIAL")
        .input(a.rsr, "--rsr")
        .output_file(a.csv, "--csv")
        .output_file(a.plot, "--plot")
        .check(a.force);
    const materials::Material m = materials::load_material(materials::material_file(a.material));
    const std::vector<double> angles =
        parse_option_value("--angles-deg", [&] { return materials::parse_angles_deg(a.angles); });
    std::vector<materials::EmissivityRow> rows;
    std::string spectral, spectral_ascii;  // the plot's Hershey font has no µ or en dash
    nlohmann::json out;
    out["material"] = m.name;
    out["file"] = a.material;
    out["model"] = m.brdf->model();
    if (a.wavelength_um) {
        rows = materials::emissivity_curve(*m.brdf, angles, *a.wavelength_um);
        spectral = fmt::format("{} µm", *a.wavelength_um);
        spectral_ascii = fmt::format("{} um", *a.wavelength_um);
        out["wavelength_um"] = *a.wavelength_um;
    } else {
        if (!(a.temperature_k > 0.0))
            usage_error("--temperature-k", "expected a temperature above 0 K, got {}",
                        a.temperature_k);
        std::optional<SpectralResponse> rsr;
        if (!a.rsr.empty()) rsr = SpectralResponse::load_csv(a.rsr);
        const Band band(a.band_um[0], a.band_um[1], rsr);
        rows = materials::emissivity_curve(*m.brdf, angles, band, a.temperature_k);
        spectral =
            fmt::format("{}–{} µm band at {} K", a.band_um[0], a.band_um[1], a.temperature_k);
        spectral_ascii =
            fmt::format("{}-{} um band at {} K", a.band_um[0], a.band_um[1], a.temperature_k);
        out["band_um"] = {a.band_um[0], a.band_um[1]};
        out["rsr"] = a.rsr.empty() ? nlohmann::json(nullptr) : nlohmann::json(a.rsr);
        out["temperature_k"] = a.temperature_k;
    }
    nlohmann::json jrows = nlohmann::json::array();
    for (const auto& r : rows)
        jrows.push_back({{"angle_deg", r.angle_deg},
                         {"e_s0", r.e(0)},
                         {"e_s1", r.e(1)},
                         {"e_s2", r.e(2)},
                         {"e_s3", r.e(3)},
                         {"dolp", r.dolp},
                         {"dhr", r.dhr}});
    out["rows"] = jrows;
    if (!a.csv.empty()) write_file_atomic(a.csv, materials::emissivity_csv(rows));
    if (!a.plot.empty())
        materials::write_emissivity_plot(a.plot, rows, m.name + ", " + spectral_ascii);
    if (a.json) {
        std::printf("%s\n", json_text(out, 2).c_str());
        return;
    }
    std::printf(
        "%s (%s), %s; Stokes in the s/p frame, S1 < 0 = polarized in the plane of emission\n",
        m.name.c_str(), m.brdf->model().c_str(), spectral.c_str());
    std::printf("%9s %9s %9s %9s %9s %8s %8s\n", "angle_deg", "e_s0", "e_s1", "e_s2", "e_s3",
                "dolp", "dhr");
    // Rounding noise of symmetric integrals (|x| ~ 1e-17) would print as "-0.00000".
    const auto shown = [](double x) { return std::abs(x) < 5e-7 ? 0.0 : x; };
    for (const auto& r : rows)
        std::printf("%9.2f %9.5f %9.5f %9.5f %9.5f %8.5f %8.5f\n", r.angle_deg, r.e(0),
                    shown(r.e(1)), shown(r.e(2)), shown(r.e(3)), shown(r.dolp), r.dhr);
    if (!a.csv.empty()) std::printf("table: %s\n", a.csv.c_str());
    if (!a.plot.empty()) std::printf("plot:  %s\n", a.plot.c_str());
}

void register_emissivity(CLI::App& app) {
    auto args = std::make_shared<EmissivityArgs>();
    auto* cmd =
        app.add_subcommand("emissivity", "Polarized directional emissivity of a material vs angle");
    cmd->add_option("material", args->material,
                    "Material YAML file or library name (flat_black_paint; docs/materials.md)")
        ->required();
    auto* wl =
        cmd->add_option("--wavelength-um", args->wavelength_um, "One wavelength in micrometres");
    auto* band = cmd->add_option("--band-um", args->band_um, "Band limits LO HI in micrometres")
                     ->expected(2);
    wl->excludes(band);
    cmd->add_option("--rsr", args->rsr, "Relative spectral response CSV (wavelength_um,response)")
        ->check(CLI::ExistingFile)
        ->needs(band);
    cmd->add_option("--angles-deg", args->angles,
                    "Emission angles: list 0,45,60 or range START:STOP:STEP")
        ->required();
    cmd->add_option("--temperature-k", args->temperature_k,
                    "Surface temperature for the Planck weighting of a band")
        ->capture_default_str();
    cmd->add_option("--csv", args->csv, "Write angle_deg,e_s0,e_s1,e_s2,e_s3,dolp,dhr to this CSV");
    cmd->add_option("--plot", args->plot,
                    "Write a PNG plot of e_s0 and e_s1 vs angle (paper Fig. 1)");
    cmd->add_flag("--json", args->json, "Print JSON (keys in docs/materials.md)");
    add_force_flag(cmd, args->force);
    cmd->callback([args, wl, band] {
        if (wl->count() == 0 && band->count() == 0)
            throw CLI::RequiredError("one of --wavelength-um or --band-um");
        run_emissivity(*args);
    });
}
}  // namespace

TIRPOL_REGISTER_COMMAND(210, register_emissivity);

}  // namespace tirpol::cli
