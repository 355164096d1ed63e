// `tirpol fit`: micro-facet pBRDF parameters from measured polarized emissivity (docs/fitting.md).

#include <cstdio>
#include <memory>

#include "cli.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/error.h"
#include "tirpol/core/utc_time.h"
#include "tirpol/core/utf8.h"
#include "tirpol/fitting/fit_output.h"
#include "tirpol/fitting/fit_plot.h"
#include "tirpol/fitting/microfacet_fit.h"
#include "tirpol/fitting/parameter_options.h"
#include "tirpol/materials/material.h"
#include "tirpol/materials/material_reference.h"
#include "tirpol/materials/microfacet.h"

namespace tirpol::cli {

namespace {

struct FitArgs {
    std::vector<std::string> data;
    std::string model = "micro-facet";
    std::vector<std::string> fix, free, bounds;
    std::string init;
    int starts = 16;
    std::uint64_t seed = 1;
    int order = 4;
    double wavelength_um = 10.0;
    std::string output, plot, name;
    bool scale_covariance = false;
    bool json = false;
    bool force = false;
};

// The fit's settings as a command line, for the provenance record.
std::string command_line(const FitArgs& a) {
    std::string out = "tirpol fit";
    for (const auto& d : a.data) out += " " + d;
    auto list = [&out](const char* flag, const std::vector<std::string>& items) {
        if (items.empty()) return;
        out += std::string(" ") + flag + " ";
        for (std::size_t i = 0; i < items.size(); ++i) out += (i ? "," : "") + items[i];
    };
    list("--fix", a.fix);
    list("--free", a.free);
    list("--bound", a.bounds);
    if (!a.init.empty()) out += " --init " + a.init;
    out += fmt::format(" --starts {} --seed {} --quadrature-order {}", a.starts, a.seed, a.order);
    if (a.scale_covariance) out += " --scale-covariance";
    return out;
}

// Initial values from a material file (--init): the micro-facet parameters at the data's first
// wavelength.
void apply_init(const std::string& path, double wavelength_um,
                fitting::MicrofacetFitOptions& options) {
    const materials::Material material = materials::load_material(materials::material_file(path));
    const auto* brdf = dynamic_cast<const materials::MicrofacetBrdf*>(material.brdf.get());
    if (!brdf)
        fail("--init {}: model \"{}\" is not the micro-facet model; expected `model: microfacet`",
             path, material.brdf->model());
    const auto values = fitting::fit_order_values(brdf->at(wavelength_um));
    for (std::size_t i = 0; i < fitting::kMicrofacetParameterCount; ++i)
        options.parameters[i].initial = values[i];
}

// --bound, --free and --fix: usage errors, so also parsed once before any data file is read.
void apply_parameter_options(const FitArgs& a, fitting::MicrofacetFitOptions& o) {
    for (const std::string& item : a.bounds)
        parse_option_value("--bound", [&] { fitting::apply_parameter_bound(item, o.parameters); });
    for (const std::string& name : a.free)
        parse_option_value("--free", [&] { fitting::apply_parameter_free(name, o.parameters); });
    for (const std::string& item : a.fix)
        parse_option_value("--fix", [&] { fitting::apply_parameter_fix(item, o.parameters); });
}

fitting::MicrofacetFitOptions options_from(const FitArgs& a, double first_wavelength_um) {
    fitting::MicrofacetFitOptions o;
    o.starts = a.starts;
    o.seed = a.seed;
    o.quadrature.order = a.order;
    o.scale_covariance_by_reduced_chi2 = a.scale_covariance;
    if (!a.init.empty()) apply_init(a.init, first_wavelength_um, o);
    apply_parameter_options(a, o);
    return o;
}

void run_fit(const FitArgs& a) {
    OutputGuard guard;
    for (const std::string& file : a.data) guard.input(file, "DATA");
    guard.input(a.init, "--init")
        .output_file(a.output, "--output")
        .output_file(a.plot, "--plot")
        .check(a.force);
    if (a.model != "micro-facet" && a.model != "microfacet")
        usage_error("--model",
                    "{}: only the micro-facet model can be fitted (expected micro-facet)", a.model);
    fitting::MicrofacetFitOptions usage_check;
    apply_parameter_options(a, usage_check);
    std::vector<fitting::EmissivityDataset> datasets;
    for (const std::string& file : a.data)
        for (auto& d : fitting::load_emissivity_csv(file, a.wavelength_um))
            datasets.push_back(std::move(d));
    const fitting::MicrofacetFitOptions options = options_from(a, datasets.front().wavelength_um);
    const fitting::MicrofacetFitProblem problem(datasets, options);
    const fitting::MicrofacetFitResult result = problem.solve();

    const fitting::FitProvenance provenance{a.data, utc_now_iso8601(), command_line(a)};
    const std::string name =
        a.name.empty() ? std::filesystem::path(a.output).stem().string() : a.name;
    write_file_atomic(a.output, fitting::fitted_material_yaml(name, result, provenance));
    if (!a.plot.empty())
        fitting::write_fit_plot(a.plot, problem.datasets(), result,
                                fmt::format("{}: polarized emissivity, measured and fitted", name),
                                options.quadrature);
    if (a.json) {
        nlohmann::json j = fitting::fit_report_json(result, problem.datasets(), provenance);
        j["material_file"] = a.output;
        j["plot_file"] = a.plot.empty() ? nlohmann::json(nullptr) : nlohmann::json(a.plot);
        std::printf("%s\n", json_text(j, 2).c_str());
    } else {
        std::printf("%s", fitting::fit_report_text(result, problem.datasets()).c_str());
        std::printf("material: %s\n", a.output.c_str());
        if (!a.plot.empty()) std::printf("plot: %s\n", a.plot.c_str());
    }
    if (!result.usable)
        fail("the fit did not converge to a usable solution ({})", result.termination);
}

void register_fit(CLI::App& app) {
    auto args = std::make_shared<FitArgs>();
    auto* cmd = app.add_subcommand(
        "fit", "Fit micro-facet pBRDF parameters to measured polarized emissivity");
    cmd->add_option("data", args->data,
                    "Emissivity CSV(s) from `tirpol extract-emissivity` (docs/fitting.md)")
        ->required()
        ->check(CLI::ExistingFile);
    cmd->add_option("--model", args->model, "Model to fit (micro-facet)")->capture_default_str();
    cmd->add_option("--fix", args->fix,
                    "Hold parameters fixed: NAME[=VALUE],... (n k sigma bias tau_deg omega_deg "
                    "rho_d rho_v)")
        ->delimiter(',');
    cmd->add_option("--free", args->free, "Free parameters that are fixed by default: NAME,...")
        ->delimiter(',');
    cmd->add_option("--bound", args->bounds, "Bounds: NAME=LOWER:UPPER,...")->delimiter(',');
    cmd->add_option(
        "--init", args->init,
        "Material YAML or library name whose micro-facet parameters are the first start");
    cmd->add_option("--starts", args->starts, "Number of starts (initial + Latin hypercube)")
        ->capture_default_str();
    cmd->add_option("--seed", args->seed, "Seed of the Latin hypercube")->capture_default_str();
    cmd->add_option("--quadrature-order", args->order, "Gauss–Legendre nodes per panel")
        ->capture_default_str();
    cmd->add_option("--wavelength-um", args->wavelength_um,
                    "Effective wavelength of data without a wavelength_um column")
        ->capture_default_str();
    cmd->add_flag(
        "--scale-covariance", args->scale_covariance,
        "Scale the covariance by chi2/dof (when the stated uncertainties are not trusted)");
    cmd->add_option("-o,--output", args->output, "Fitted material YAML")->required();
    cmd->add_option("--name", args->name, "Material name (default: the output file's stem)");
    cmd->add_option("--plot", args->plot, "PNG plot of data and fit (like the paper's Fig. 1)");
    cmd->add_flag("--json", args->json, "Print the fit report as JSON (keys in docs/fitting.md)");
    add_force_flag(cmd, args->force);
    cmd->callback([args] { run_fit(*args); });
}

}  // namespace

TIRPOL_REGISTER_COMMAND(600, register_fit);

}  // namespace tirpol::cli
