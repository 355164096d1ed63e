// `tirpol temperature`: counts → radiance → brightness temperature with a radiometric calibration.

#include <cstdio>
#include <memory>
#include <optional>
#include <variant>

#include "cli.h"
#include "tirpol/calibration/calibration_quality.h"
#include "tirpol/calibration/radiometric.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/raster_io.h"

namespace tirpol::cli {

namespace {
/// The FPA temperature given on the command line, else the one a session frame's header carries.
std::optional<double> frame_fpa_temperature_k(const Image& raw, std::optional<double> given) {
    if (given) return given;
    const auto it = raw.attributes().find("fpa_temperature_k");
    if (it != raw.attributes().end())
        if (const double* t = std::get_if<double>(&it->second)) return *t;
    return std::nullopt;
}

struct TemperatureArgs {
    std::string image, calibration, output, channel = "counts";
    std::optional<double> fpa_temperature_k;
    bool force = false;
};

void run_temperature(const TemperatureArgs& a) {
    OutputGuard()
        .input(a.image, "IMAGE")
        .input(a.calibration, "--calibration")
        .output_file(a.output, "--output")
        .check(a.force);
    const auto cal = calibration::read_radiometric_calibration(a.calibration);
    const Image raw = read_raw_image(a.image, "counts", a.channel);
    if (raw.width() != cal.width || raw.height() != cal.height)
        fail("{}: image is {}×{} but calibration {} is {}×{}", a.image, raw.width(), raw.height(),
             a.calibration, cal.width, cal.height);
    const auto fpa_k = frame_fpa_temperature_k(raw, a.fpa_temperature_k);
    const auto radiance = calibration::counts_to_radiance(cal, raw.channel("counts"), fpa_k);
    const auto warning = calibration::extrapolation_warning(cal, radiance, fpa_k);
    Image out(raw.width(), raw.height());
    out.set_channel("radiance", radiance);
    out.set_channel("temperature_k", calibration::brightness_temperature(cal.band(), radiance));
    if (channel_stats(out.channel("temperature_k")).finite_count == 0)
        fail(
            "{}: no pixel gives a finite brightness temperature with calibration {} (counts below "
            "its offsets "
            "everywhere: another camera, bit depth or gain setting?); nothing written",
            a.image, a.calibration);
    out.attributes()["units_radiance"] = std::string("W/(m^2 sr)");
    out.attributes()["units_temperature_k"] = std::string("K");
    out.attributes()["band_um"] = std::vector<double>{cal.band_lo_um, cal.band_hi_um};
    out.attributes()["calibration"] = a.calibration;
    out.attributes()["source"] = a.image;
    if (warning) out.attributes()["calibration_warning"] = *warning;
    write_exr(a.output, out);
    if (warning) std::printf("warning: %s\n", warning->c_str());
    const auto stats = channel_stats(out.channel("temperature_k"));
    std::printf("brightness temperature: min %.2f K, mean %.2f K, max %.2f K → %s\n", stats.min,
                stats.mean, stats.max, a.output.c_str());
}

void register_temperature(CLI::App& app) {
    auto a = std::make_shared<TemperatureArgs>();
    auto* cmd = app.add_subcommand(
        "temperature", "Brightness-temperature image from counts and a radiometric calibration");
    cmd->add_option("IMAGE", a->image, "Raw image: EXR (channel --channel), 16-bit PNG or TIFF")
        ->required()
        ->check(CLI::ExistingFile);
    cmd->add_option("--calibration", a->calibration, "Radiometric calibration EXR")
        ->required()
        ->check(CLI::ExistingFile);
    cmd->add_option("--channel", a->channel, "EXR channel holding counts")->capture_default_str();
    cmd->add_option("--fpa-temperature-k", a->fpa_temperature_k,
                    "Camera FPA temperature of the image (default: the EXR's fpa_temperature_k "
                    "attribute); needed by an "
                    "FPA-dependent calibration");
    cmd->add_option("-o,--output", a->output, "Output EXR (radiance, temperature_k)")->required();
    add_force_flag(cmd, a->force);
    cmd->callback([a] { run_temperature(*a); });
}
}  // namespace

TIRPOL_REGISTER_COMMAND(52, register_temperature);

}  // namespace tirpol::cli
