// `tirpol temperature`: counts → radiance → brightness temperature with a radiometric calibration.

#include "cli.h"
#include "common_options.h"
#include "tirpol/calibration/radiometric.h"

namespace tirpol::cli {

namespace {
void register_temperature(CLI::App& app) {
    auto o = std::make_shared<calibration::TemperatureImageOptions>();
    auto* cmd = app.add_subcommand(
        "temperature", "Brightness-temperature image from counts and a radiometric calibration");
    add_required_input(cmd, "IMAGE", o->image,
                       "Raw image: EXR (channel --channel), 16-bit PNG or TIFF");
    add_required_input(cmd, "--calibration", o->calibration, "Radiometric calibration EXR");
    cmd->add_option("--channel", o->channel, "EXR channel holding counts")->capture_default_str();
    cmd->add_option("--fpa-temperature-k", o->fpa_temperature_k,
                    "Camera FPA temperature of the image (default: the EXR's fpa_temperature_k "
                    "attribute); needed by an FPA-dependent calibration");
    add_output_option(cmd, o->output, "Output EXR (radiance, temperature_k)");
    add_force_flag(cmd, o->force);
    cmd->callback([o] {
        print_text(
            calibration::temperature_image_text(calibration::brightness_temperature_image(*o)));
    });
}
}  // namespace

TIRPOL_REGISTER_COMMAND(52, register_temperature);

}  // namespace tirpol::cli
