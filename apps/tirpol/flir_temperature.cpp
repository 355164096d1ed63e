// `tirpol flir-temperature`: raw FLIR counts → object temperature with the camera's Planck
// constants and FLIR's corrections for emissivity, reflected temperature, atmosphere and an
// external window.

#include <optional>

#include "cli.h"
#include "common_options.h"
#include "tirpol/calibration/flir_image.h"
#include "tirpol/core/radiometry.h"

namespace tirpol::cli {

namespace {
struct FlirArgs {
    calibration::FlirImageOptions options;
    std::vector<double> planck;
    double reflected_c = 20.0;
    std::optional<double> atmosphere_c, window_c;
};

void run_flir(FlirArgs& a) {
    auto& o = a.options;
    o.planck = {a.planck[0], a.planck[1], a.planck[2], a.planck[3], a.planck[4]};
    o.conditions.reflected_k = a.reflected_c + kZeroCelsiusK;
    o.conditions.atmosphere_k = a.atmosphere_c.value_or(a.reflected_c) + kZeroCelsiusK;
    o.conditions.window_k = a.window_c.value_or(a.reflected_c) + kZeroCelsiusK;
    print_text(calibration::flir_image_text(calibration::flir_temperature_image(o)));
}

void register_flir(CLI::App& app) {
    auto a = std::make_shared<FlirArgs>();
    auto& c = a->options.conditions;
    auto* cmd = app.add_subcommand("flir-temperature",
                                   "Object temperature from FLIR raw counts and Planck constants");
    add_required_input(cmd, "RAW_IMAGE", a->options.image, "Raw image: EXR, 16-bit PNG or TIFF");
    cmd->add_option("--planck", a->planck,
                    "R1,R2,B,F,O (EXIF PlanckR1, PlanckR2, PlanckB, PlanckF, PlanckO)")
        ->required()
        ->expected(5)
        ->delimiter(',');
    cmd->add_option("--channel", a->options.channel, "EXR channel holding raw counts")
        ->capture_default_str();
    cmd->add_option("--emissivity", c.emissivity, "Object emissivity (0, 1]")
        ->capture_default_str();
    cmd->add_option("--distance-m", c.distance_m, "Object distance in metres")
        ->capture_default_str();
    cmd->add_option("--reflected-c", a->reflected_c, "Reflected apparent temperature, °C")
        ->capture_default_str();
    cmd->add_option("--atmosphere-c", a->atmosphere_c, "Air temperature, °C (default: reflected)");
    cmd->add_option("--humidity-pct", c.humidity_pct, "Relative humidity, %")
        ->capture_default_str();
    cmd->add_option("--window-c", a->window_c,
                    "External IR window temperature, °C (default: reflected)");
    cmd->add_option("--window-transmission", c.window_transmission,
                    "External IR window transmission (0, 1]")
        ->capture_default_str();
    add_output_option(cmd, a->options.output, "Output EXR (temperature_k)");
    add_force_flag(cmd, a->options.force);
    cmd->callback([a] { run_flir(*a); });
}
}  // namespace

TIRPOL_REGISTER_COMMAND(53, register_flir);

}  // namespace tirpol::cli
