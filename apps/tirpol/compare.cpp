// `tirpol compare`: measured vs simulated Stokes images → a self-contained HTML report, report.json
// and PNGs (docs/report.md).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <optional>

#include "cli.h"
#include "invocation.h"
#include "tirpol/core/camera_model.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/report/comparison_report.h"
#include "tirpol/report/summary_text.h"

namespace tirpol::cli {

namespace {

struct CompareArgs {
    std::string measured, simulated, rois, control_points, camera, registration, output;
    std::optional<double> measured_sigma;
    double gain_sigma = 0.0, offset_sigma = 0.0, false_alarm = 0.05, power = 0.80;
    std::vector<double> band_um;
    bool json = false;
    bool force = false;
};

void run_compare(const CompareArgs& a) {
    using namespace tirpol::report;
    CompareOptions options;
    options.measured_name = a.measured;
    options.simulated_name = a.simulated;
    if (!a.control_points.empty()) options.control_points = load_control_points(a.control_points);
    if (!a.camera.empty()) {
        options.camera_model = read_camera_model(a.camera);
        options.camera_model_name = a.camera;
    }
    // Default: the camera model when given, else control points when given, else automatic.
    options.registration =
        !a.registration.empty()
            ? parse_option_value("--registration",
                                 [&] { return parse_registration_method(a.registration); })
        : !a.camera.empty()         ? RegistrationMethod::CameraModel
        : !a.control_points.empty() ? RegistrationMethod::ControlPoints
                                    : RegistrationMethod::Auto;
    if (options.registration == RegistrationMethod::ControlPoints && a.control_points.empty())
        usage_error("--registration", "control-points needs --control-points CP.yaml");
    if (options.registration == RegistrationMethod::CameraModel && a.camera.empty())
        usage_error("--registration", "camera-model needs --camera CAM.yaml");
    if (!a.camera.empty() && options.registration != RegistrationMethod::CameraModel)
        usage_error(
            "--camera",
            "a camera model registers by the model: leave out --registration or give camera-model");
    if (!a.rois.empty()) options.regions = load_regions(a.rois);
    if (a.measured_sigma) {
        if (!(*a.measured_sigma > 0.0) || !std::isfinite(*a.measured_sigma))
            usage_error("--measured-sigma", "expected a positive radiance in W/(m²·sr), got {}",
                        *a.measured_sigma);
        options.measured_frame_sigma = a.measured_sigma;
    }
    if (!(a.gain_sigma >= 0.0 && a.gain_sigma < 1.0))
        usage_error("--gain-sigma", "expected a relative gain uncertainty in [0, 1), got {}",
                    a.gain_sigma);
    if (!(a.offset_sigma >= 0.0) || !std::isfinite(a.offset_sigma))
        usage_error("--offset-sigma", "expected a non-negative radiance in W/(m²·sr), got {}",
                    a.offset_sigma);
    if (!(a.false_alarm > 0.0 && a.false_alarm < 0.5))
        usage_error("--false-alarm", "expected a probability in (0, 0.5), got {}", a.false_alarm);
    if (!(a.power > 0.5 && a.power < 1.0))
        usage_error("--power", "expected a probability in (0.5, 1), got {}", a.power);
    options.measured_gain_sigma_relative = a.gain_sigma;
    options.measured_offset_sigma = a.offset_sigma;
    options.design.false_alarm_per_region = a.false_alarm;
    options.design.power = a.power;
    if (!a.band_um.empty()) options.band_um = std::array<double, 2>{a.band_um[0], a.band_um[1]};
    OutputGuard()
        .input(a.measured, "--measured")
        .input(a.simulated, "--simulated")
        .input(a.rois, "--rois")
        .input(a.control_points, "--control-points")
        .input(a.camera, "--camera")
        .output_folder(a.output, "--output",
                       {"report.html", "report.json", "comparison.exr", "*.png", "*.svg"})
        .check(a.force);
    const Image measured = read_exr(a.measured);
    const Image simulated = read_exr(a.simulated);
    options.provenance.tool_version = version_text();
    options.provenance.command_line = command_line_text();
    options.provenance.inputs.push_back(describe_input("measured", a.measured, &measured));
    options.provenance.inputs.push_back(describe_input("simulated", a.simulated, &simulated));
    if (!a.rois.empty()) options.provenance.inputs.push_back(describe_input("regions", a.rois));
    if (!a.control_points.empty())
        options.provenance.inputs.push_back(describe_input("control points", a.control_points));
    if (!a.camera.empty())
        options.provenance.inputs.push_back(describe_input("camera model", a.camera));
    const CompareResult r = write_comparison_report(measured, simulated, options, a.output);
    std::printf("%s", (a.json ? comparison_json(r) : comparison_text(r)).c_str());
}

void register_compare(CLI::App& app) {
    auto args = std::make_shared<CompareArgs>();
    auto* cmd = app.add_subcommand(
        "compare", "Measured vs simulated Stokes images → HTML report with statistics");
    cmd->add_option("--measured", args->measured, "Measured Stokes EXR (from `tirpol reduce`)")
        ->required()
        ->check(CLI::ExistingFile);
    cmd->add_option("--simulated", args->simulated, "Simulated Stokes EXR (from `tirpol render`)")
        ->required()
        ->check(CLI::ExistingFile);
    cmd->add_option("--rois", args->rois,
                    "Regions of interest YAML (named polygons in measured pixels)")
        ->check(CLI::ExistingFile);
    cmd->add_option("--control-points", args->control_points,
                    "Control points YAML (measured ↔ simulated pixels)")
        ->check(CLI::ExistingFile);
    cmd->add_option("--camera", args->camera,
                    "The measured camera's model YAML (`tirpol calibrate geometric`) the "
                    "simulation was rendered through: "
                    "no warp, the residual misalignment is measured")
        ->check(CLI::ExistingFile);
    cmd->add_option("--registration", args->registration,
                    "none | auto | control-points | camera-model (default: camera-model with "
                    "--camera, else control-points "
                    "if given, else auto)")
        ->check(CLI::IsMember({"none", "auto", "control-points", "camera-model"}));
    cmd->add_option("--measured-sigma", args->measured_sigma,
                    "Radiance noise of one polarizer frame, W/(m²·sr), when the measured EXR has "
                    "no *_std channels");
    cmd->add_option(
        "--gain-sigma", args->gain_sigma,
        "Relative calibration gain uncertainty common to every pixel (e.g. 0.005), default 0");
    cmd->add_option(
        "--offset-sigma", args->offset_sigma,
        "S0 calibration offset uncertainty common to every pixel, W/(m²·sr), default 0");
    cmd->add_option("--false-alarm", args->false_alarm,
                    "False-alarm probability per region (default 0.05)");
    cmd->add_option("--power", args->power,
                    "Power at which the detectable bias is quoted (default 0.80)");
    cmd->add_option("--band-um", args->band_um,
                    "Band LO HI in µm for the S0 bias in kelvin (default: the EXRs' band_um)")
        ->expected(2);
    cmd->add_option("-o,--output", args->output, "Report directory (created)")->required();
    cmd->add_flag("--json", args->json, "Print report.json to stdout instead of the summary");
    add_force_flag(cmd, args->force);
    cmd->callback([args] { run_compare(*args); });
}

}  // namespace

TIRPOL_REGISTER_COMMAND(700, register_compare);

}  // namespace tirpol::cli
