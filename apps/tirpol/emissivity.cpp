// `tirpol emissivity`: polarized directional emissivity of a material versus emission angle, at one
// wavelength or averaged over a band (Planck × RSR weighted), as a table, CSV, JSON and a Fig.
// 1-style plot.

#include "tirpol/materials/emissivity.h"

#include "cli.h"
#include "common_options.h"
#include "tirpol/core/limits.h"

namespace tirpol::cli {

namespace {
struct EmissivityArgs {
    materials::EmissivityReportOptions options;
    std::vector<double> band_um;
    std::string angles;
    bool json = false;
};

void run_emissivity(EmissivityArgs& a) {
    auto& o = a.options;
    o.angles_deg =
        parse_option_value("--angles-deg", [&] { return materials::parse_angles_deg(a.angles); });
    if (!o.wavelength_um) o.band_um = {a.band_um[0], a.band_um[1]};
    const materials::EmissivityReport report = materials::emissivity_report(o);
    a.json ? print_json(materials::emissivity_report_json(report))
           : print_text(materials::emissivity_report_text(report));
}

void register_emissivity(CLI::App& app) {
    auto args = std::make_shared<EmissivityArgs>();
    auto& o = args->options;
    auto* cmd =
        app.add_subcommand("emissivity", "Polarized directional emissivity of a material vs angle");
    cmd->add_option("material", o.material,
                    "Material YAML file or library name (flat_black_paint; docs/materials.md)")
        ->required();
    auto* wl = cmd->add_option("--wavelength-um", o.wavelength_um, "One wavelength in micrometres");
    auto* band = add_band_options(cmd, args->band_um, o.rsr);
    wl->excludes(band);
    cmd->get_option("--rsr")->needs(band);
    cmd->add_option("--angles-deg", args->angles,
                    "Emission angles: list 0,45,60 or range START:STOP:STEP")
        ->required();
    cmd->add_option("--temperature-k", o.temperature_k,
                    "Surface temperature for the Planck weighting of a band")
        ->capture_default_str();
    cmd->add_option("--csv", o.csv, "Write angle_deg,e_s0,e_s1,e_s2,e_s3,dolp,dhr to this CSV");
    cmd->add_option("--plot", o.plot, "Write a PNG plot of e_s0 and e_s1 vs angle (paper Fig. 1)");
    add_json_flag(cmd, args->json, "Print JSON (keys in docs/materials.md)");
    add_force_flag(cmd, o.force);
    cmd->callback([args, wl, band] {
        if (wl->count() == 0 && band->count() == 0)
            throw CLI::RequiredError("one of --wavelength-um or --band-um");
        run_emissivity(*args);
    });
}
}  // namespace

TIRPOL_REGISTER_COMMAND(210, register_emissivity);

}  // namespace tirpol::cli
