// `tirpol brdf`: the Mueller BRDF of a material for one pair of directions.

#include "cli.h"
#include "common_options.h"
#include "tirpol/core/limits.h"
#include "tirpol/materials/material.h"

namespace tirpol::cli {

namespace {
void run_brdf(materials::BrdfEvaluationOptions options, const std::vector<double>& incident,
              const std::vector<double>& exitant, bool json) {
    for (const auto& [name, angles] :
         {std::pair{"--incident-deg", &incident}, std::pair{"--exitant-deg", &exitant}})
        parse_option_value(name, [&] {
            return materials::direction_from_zenith_azimuth_deg((*angles)[0], (*angles)[1]);
        });
    options.incident_deg = {incident[0], incident[1]};
    options.exitant_deg = {exitant[0], exitant[1]};
    const materials::BrdfEvaluation e = materials::evaluate_brdf(options);
    json ? print_json(materials::brdf_evaluation_json(e))
         : print_text(materials::brdf_evaluation_text(e));
}

void register_brdf(CLI::App& app) {
    auto options = std::make_shared<materials::BrdfEvaluationOptions>();
    auto incident = std::make_shared<std::vector<double>>();
    auto exitant = std::make_shared<std::vector<double>>();
    auto json = std::make_shared<bool>(false);
    auto* cmd =
        app.add_subcommand("brdf", "Mueller BRDF of a material for one incident/exitant pair");
    cmd->add_option("material", options->material,
                    "Material YAML file or library name (flat_black_paint; docs/materials.md)")
        ->required();
    cmd->add_option("--wavelength-um", options->wavelength_um, "Wavelength in micrometres")
        ->required();
    cmd->add_option("--incident-deg", *incident, "Incident zenith and azimuth TH PHI (degrees)")
        ->required()
        ->expected(2);
    cmd->add_option("--exitant-deg", *exitant, "Exitant zenith and azimuth TH PHI (degrees)")
        ->required()
        ->expected(2);
    add_json_flag(cmd, *json);
    cmd->callback([=] { run_brdf(*options, *incident, *exitant, *json); });
}
}  // namespace

TIRPOL_REGISTER_COMMAND(220, register_brdf);

}  // namespace tirpol::cli
