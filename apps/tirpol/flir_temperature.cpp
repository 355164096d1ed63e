// `tirpol flir-temperature`: raw FLIR counts → object temperature with the camera's Planck
// constants and FLIR's corrections for emissivity, reflected temperature, atmosphere and an
// external window.

#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>

#include "cli.h"
#include "tirpol/calibration/flir.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/radiometry.h"
#include "tirpol/core/raster_io.h"

namespace tirpol::cli {

namespace {
struct FlirArgs {
    std::string image, output, channel = "counts";
    std::vector<double> planck;
    double emissivity = 1.0, distance_m = 0.0, reflected_c = 20.0, humidity_pct = 50.0,
           window_transmission = 1.0;
    std::optional<double> atmosphere_c, window_c;
    bool force = false;
};

void run_flir(const FlirArgs& a) {
    OutputGuard().input(a.image, "RAW_IMAGE").output_file(a.output, "--output").check(a.force);
    const calibration::FlirPlanck p{a.planck[0], a.planck[1], a.planck[2], a.planck[3],
                                    a.planck[4]};
    calibration::FlirConditions c;
    c.emissivity = a.emissivity;
    c.distance_m = a.distance_m;
    c.reflected_k = a.reflected_c + kZeroCelsiusK;
    c.atmosphere_k = a.atmosphere_c.value_or(a.reflected_c) + kZeroCelsiusK;
    c.window_k = a.window_c.value_or(a.reflected_c) + kZeroCelsiusK;
    c.humidity_pct = a.humidity_pct;
    c.window_transmission = a.window_transmission;
    calibration::validate_flir(p, c);
    const Image raw = read_raw_image(a.image, "counts", a.channel);
    Image out(raw.width(), raw.height());
    auto& t = out.add_channel("temperature_k");
    const auto& counts = raw.channel("counts");
    std::size_t invalid = 0;
    for (std::size_t i = 0; i < counts.size(); ++i) {
        t[i] = static_cast<float>(calibration::flir_temperature_from_raw(p, counts[i], c));
        if (!std::isfinite(t[i])) ++invalid;
    }
    auto& at = out.attributes();
    at["units_temperature_k"] = std::string("K");
    at["planck_r1_r2_b_f_o"] = a.planck;
    at["emissivity"] = c.emissivity;
    at["distance_m"] = c.distance_m;
    at["reflected_k"] = c.reflected_k;
    at["atmosphere_k"] = c.atmosphere_k;
    at["humidity_pct"] = c.humidity_pct;
    at["window_k"] = c.window_k;
    at["window_transmission"] = c.window_transmission;
    at["atmospheric_transmission_half_path"] = calibration::flir_atmospheric_transmission(
        c.distance_m / 2.0, c.atmosphere_k, c.humidity_pct);
    at["source"] = a.image;
    write_exr(a.output, out);
    const auto s = channel_stats(t);
    std::printf(
        "object temperature: min %.2f °C, mean %.2f °C, max %.2f °C (%zu pixel(s) without a "
        "solution) → %s\n",
        s.min - kZeroCelsiusK, s.mean - kZeroCelsiusK, s.max - kZeroCelsiusK, invalid,
        a.output.c_str());
}

void register_flir(CLI::App& app) {
    auto a = std::make_shared<FlirArgs>();
    auto* cmd = app.add_subcommand("flir-temperature",
                                   "Object temperature from FLIR raw counts and Planck constants");
    cmd->add_option("RAW_IMAGE", a->image, "Raw image: EXR, 16-bit PNG or TIFF")
        ->required()
        ->check(CLI::ExistingFile);
    cmd->add_option("--planck", a->planck,
                    "R1,R2,B,F,O (EXIF PlanckR1, PlanckR2, PlanckB, PlanckF, PlanckO)")
        ->required()
        ->expected(5)
        ->delimiter(',');
    cmd->add_option("--channel", a->channel, "EXR channel holding raw counts")
        ->capture_default_str();
    cmd->add_option("--emissivity", a->emissivity, "Object emissivity (0, 1]")
        ->capture_default_str();
    cmd->add_option("--distance-m", a->distance_m, "Object distance in metres")
        ->capture_default_str();
    cmd->add_option("--reflected-c", a->reflected_c, "Reflected apparent temperature, °C")
        ->capture_default_str();
    cmd->add_option("--atmosphere-c", a->atmosphere_c, "Air temperature, °C (default: reflected)");
    cmd->add_option("--humidity-pct", a->humidity_pct, "Relative humidity, %")
        ->capture_default_str();
    cmd->add_option("--window-c", a->window_c,
                    "External IR window temperature, °C (default: reflected)");
    cmd->add_option("--window-transmission", a->window_transmission,
                    "External IR window transmission (0, 1]")
        ->capture_default_str();
    cmd->add_option("-o,--output", a->output, "Output EXR (temperature_k)")->required();
    add_force_flag(cmd, a->force);
    cmd->callback([a] { run_flir(*a); });
}
}  // namespace

TIRPOL_REGISTER_COMMAND(53, register_flir);

}  // namespace tirpol::cli
