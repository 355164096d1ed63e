// `tirpol compare`: measured vs simulated Stokes images → a self-contained HTML report, report.json
// and PNGs (docs/report.md).

#include <cmath>
#include <array>
#include <cstdio>
#include <optional>

#include "cli.h"
#include "invocation.h"
#include "tirpol/core/camera_model.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/report/comparison_report.h"

namespace tirpol::cli {

namespace {

struct CompareArgs {
    std::string measured, simulated, rois, control_points, camera, registration, output;
    std::optional<double> measured_sigma;
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
    options.registration = !a.registration.empty()
                               ? parse_option_value("--registration",
                                                    [&] { return parse_registration_method(a.registration); })
                           : !a.camera.empty()          ? RegistrationMethod::CameraModel
                           : !a.control_points.empty() ? RegistrationMethod::ControlPoints
                                                        : RegistrationMethod::Auto;
    if (options.registration == RegistrationMethod::ControlPoints && a.control_points.empty())
        usage_error("--registration", "control-points needs --control-points CP.yaml");
    if (options.registration == RegistrationMethod::CameraModel && a.camera.empty())
        usage_error("--registration", "camera-model needs --camera CAM.yaml");
    if (!a.camera.empty() && options.registration != RegistrationMethod::CameraModel)
        usage_error("--camera", "a camera model registers by the model: leave out --registration or give camera-model");
    if (!a.rois.empty()) options.regions = load_regions(a.rois);
    if (a.measured_sigma) {
        if (!(*a.measured_sigma > 0.0) || !std::isfinite(*a.measured_sigma))
            usage_error("--measured-sigma", "expected a positive radiance in W/(m²·sr), got {}", *a.measured_sigma);
        options.measured_frame_sigma = a.measured_sigma;
    }
    if (!a.band_um.empty()) options.band_um = std::array<double, 2>{a.band_um[0], a.band_um[1]};
    OutputGuard()
        .input(a.measured, "--measured")
        .input(a.simulated, "--simulated")
        .input(a.rois, "--rois")
        .input(a.control_points, "--control-points")
        .input(a.camera, "--camera")
        .output_folder(a.output, "--output", {"report.html", "report.json", "comparison.exr", "*.png", "*.svg"})
        .check(a.force);
    const Image measured = read_exr(a.measured);
    const Image simulated = read_exr(a.simulated);
    options.provenance.tool_version = version_text();
    options.provenance.command_line = command_line_text();
    options.provenance.inputs.push_back(describe_input("measured", a.measured, &measured));
    options.provenance.inputs.push_back(describe_input("simulated", a.simulated, &simulated));
    if (!a.rois.empty()) options.provenance.inputs.push_back(describe_input("regions", a.rois));
    if (!a.control_points.empty()) options.provenance.inputs.push_back(describe_input("control points", a.control_points));
    if (!a.camera.empty()) options.provenance.inputs.push_back(describe_input("camera model", a.camera));
    const CompareResult r = write_comparison_report(measured, simulated, options, a.output);
    if (a.json) {
        std::printf("%s", comparison_json(r).c_str());
        return;
    }
    const auto& g = r.registration;
    std::printf("registration: %s (%s), residual misalignment %.3f px\n", to_string(g.method).c_str(), g.model.c_str(),
                std::hypot(g.residual_shift_px[0], g.residual_shift_px[1]));
    if (!g.note.empty()) std::printf("  %s\n", g.note.c_str());
    std::printf("%-16s %9s %12s %16s %-22s %-22s %-22s %s\n", "region", "pixels", "S0 bias", "S0 bias [K]", "S0",
                "S1", "S2", "verdict");
    for (const auto& region : r.regions) {
        const auto& k = region.s0_bias_k;
        const std::string kelvin = k ? fmt::format("{:.3f}±{:.3f}", k->bias_k, k->bias_sigma_k) : "–";
        std::printf("%-16s %9zu %12.4g %16s", region.name.c_str(), region.pixel_count, region.stats.at("S0").bias,
                    kelvin.c_str());
        for (const auto& q : kZQuantities) {
            const auto& z = region.z.at(q);
            std::printf(" %-22s", fmt::format("{:.1f}% rms {:.2f} {}", 100.0 * z.fraction_above_2, z.rms,
                                              region.verdicts.at(q) == ZVerdict::Consistent          ? "ok"
                                              : region.verdicts.at(q) == ZVerdict::SigmaOverestimated ? "sigma-high"
                                              : region.verdicts.at(q) == ZVerdict::ExceedsNoise       ? "EXCEEDS"
                                                                                                      : "-")
                                      .c_str());
        }
        std::printf(" %s\n", to_string(region.verdict).c_str());
    }
    for (const auto& note : r.notes) std::printf("note: %s\n", note.c_str());
    std::printf("report: %s\n", r.html.string().c_str());
}

void register_compare(CLI::App& app) {
    auto args = std::make_shared<CompareArgs>();
    auto* cmd = app.add_subcommand("compare", "Measured vs simulated Stokes images → HTML report with statistics");
    cmd->add_option("--measured", args->measured, "Measured Stokes EXR (from `tirpol reduce`)")
        ->required()
        ->check(CLI::ExistingFile);
    cmd->add_option("--simulated", args->simulated, "Simulated Stokes EXR (from `tirpol render`)")
        ->required()
        ->check(CLI::ExistingFile);
    cmd->add_option("--rois", args->rois, "Regions of interest YAML (named polygons in measured pixels)")
        ->check(CLI::ExistingFile);
    cmd->add_option("--control-points", args->control_points, "Control points YAML (measured ↔ simulated pixels)")
        ->check(CLI::ExistingFile);
    cmd->add_option("--camera", args->camera,
                    "The measured camera's model YAML (`tirpol calibrate geometric`) the simulation was rendered through: "
                    "no warp, the residual misalignment is measured")
        ->check(CLI::ExistingFile);
    cmd->add_option("--registration", args->registration,
                    "none | auto | control-points | camera-model (default: camera-model with --camera, else control-points "
                    "if given, else auto)")
        ->check(CLI::IsMember({"none", "auto", "control-points", "camera-model"}));
    cmd->add_option("--measured-sigma", args->measured_sigma,
                    "Radiance noise of one polarizer frame, W/(m²·sr), when the measured EXR has no *_std channels");
    cmd->add_option("--band-um", args->band_um, "Band LO HI in µm for the S0 bias in kelvin (default: the EXRs' band_um)")
        ->expected(2);
    cmd->add_option("-o,--output", args->output, "Report directory (created)")->required();
    cmd->add_flag("--json", args->json, "Print report.json to stdout instead of the summary");
    add_force_flag(cmd, args->force);
    cmd->callback([args] { run_compare(*args); });
}

}  // namespace

TIRPOL_REGISTER_COMMAND(700, register_compare);

}  // namespace tirpol::cli
