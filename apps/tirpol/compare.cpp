// `tirpol compare`: measured vs simulated Stokes images → a self-contained HTML report, report.json
// and PNGs (docs/report.md).

#include <cmath>
#include <cstdio>
#include <optional>

#include "cli.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/report/comparison_report.h"

namespace tirpol::cli {

namespace {

struct CompareArgs {
    std::string measured, simulated, rois, control_points, registration, output;
    std::optional<double> measured_sigma;
    bool json = false;
};

void run_compare(const CompareArgs& a) {
    using namespace tirpol::report;
    CompareOptions options;
    options.measured_name = a.measured;
    options.simulated_name = a.simulated;
    if (!a.control_points.empty()) options.control_points = load_control_points(a.control_points);
    // Default: control points when given, automatic otherwise.
    options.registration = !a.registration.empty() ? parse_registration_method(a.registration)
                           : a.control_points.empty() ? RegistrationMethod::Auto
                                                      : RegistrationMethod::ControlPoints;
    if (options.registration == RegistrationMethod::ControlPoints && a.control_points.empty())
        fail("--registration control-points needs --control-points CP.yaml");
    if (!a.rois.empty()) options.regions = load_regions(a.rois);
    if (a.measured_sigma) {
        if (!(*a.measured_sigma > 0.0) || !std::isfinite(*a.measured_sigma))
            fail("--measured-sigma: expected a positive radiance in W/(m²·sr), got {}", *a.measured_sigma);
        options.measured_frame_sigma = a.measured_sigma;
    }
    const Image measured = read_exr(a.measured);
    const Image simulated = read_exr(a.simulated);
    const CompareResult r = write_comparison_report(measured, simulated, options, a.output);
    if (a.json) {
        std::printf("%s", comparison_json(r).c_str());
        return;
    }
    const auto& g = r.registration;
    std::printf("registration: %s (%s), residual misalignment %.3f px\n", to_string(g.method).c_str(), g.model.c_str(),
                std::hypot(g.residual_shift_px[0], g.residual_shift_px[1]));
    std::printf("%-16s %9s %12s %12s %9s %9s  %s\n", "region", "pixels", "S0 bias", "S1 bias", "|z|>2", "|z|>3",
                "verdict");
    for (const auto& region : r.regions) {
        const auto& z = region.z.at("all");
        std::printf("%-16s %9zu %12.4g %12.4g %8.2f%% %8.2f%%  %s\n", region.name.c_str(), region.pixel_count,
                    region.stats.at("S0").bias, region.stats.at("S1").bias, 100.0 * z.fraction_above_2,
                    100.0 * z.fraction_above_3, consistent_with_noise(z) ? "consistent with noise" : "exceeds noise");
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
    cmd->add_option("--registration", args->registration,
                    "none | auto | control-points (default: control-points if given, else auto)")
        ->check(CLI::IsMember({"none", "auto", "control-points"}));
    cmd->add_option("--measured-sigma", args->measured_sigma,
                    "Radiance noise of one polarizer frame, W/(m²·sr), when the measured EXR has no *_std channels");
    cmd->add_option("-o,--output", args->output, "Report directory (created)")->required();
    cmd->add_flag("--json", args->json, "Print report.json to stdout instead of the summary");
    cmd->callback([args] { run_compare(*args); });
}

}  // namespace

TIRPOL_REGISTER_COMMAND(700, register_compare);

}  // namespace tirpol::cli
