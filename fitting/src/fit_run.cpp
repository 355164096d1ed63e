#include "tirpol/fitting/fit_run.h"

#include <fmt/format.h>

#include <filesystem>

#include "tirpol/core/atomic_file.h"
#include "tirpol/core/limits.h"
#include "tirpol/core/output_guard.h"
#include "tirpol/core/utc_time.h"
#include "tirpol/materials/material.h"
#include "tirpol/materials/microfacet.h"

namespace tirpol::fitting {

namespace {
// The fit's settings as a command line, for the provenance record.
std::string command_line(const FitRunOptions& a) {
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
    out += fmt::format(" --starts {} --seed {} --quadrature-order {}", a.starts, a.seed,
                       a.quadrature_order);
    if (a.scale_covariance) out += " --scale-covariance";
    return out;
}

// Initial values from a material file (--init): the micro-facet parameters at the data's first
// wavelength.
void apply_init(const std::string& path, double wavelength_um, MicrofacetFitOptions& options) {
    const materials::Material material = materials::load_material(materials::material_file(path));
    const auto* brdf = dynamic_cast<const materials::MicrofacetBrdf*>(material.brdf.get());
    if (!brdf)
        fail("--init {}: model \"{}\" is not the micro-facet model; expected `model: microfacet`",
             path, material.brdf->model());
    const auto values = fit_order_values(brdf->at(wavelength_um));
    for (std::size_t i = 0; i < kMicrofacetParameterCount; ++i)
        options.parameters[i].initial = values[i];
}

template <typename Apply>
void as_option_error(const char* option, Apply&& apply) {
    try {
        apply();
    } catch (const Error& e) {
        throw OptionValueError(option, e.what());
    }
}
}  // namespace

void apply_parameter_options(const FitRunOptions& a, ParameterSettings& settings) {
    for (const std::string& item : a.bounds)
        as_option_error("--bound", [&] { apply_parameter_bound(item, settings); });
    for (const std::string& name : a.free)
        as_option_error("--free", [&] { apply_parameter_free(name, settings); });
    for (const std::string& item : a.fix)
        as_option_error("--fix", [&] { apply_parameter_fix(item, settings); });
}

FitRun run_fit(const FitRunOptions& a) {
    OutputGuard guard;
    for (const std::string& file : a.data) guard.input(file, "DATA");
    guard.input(a.init, "--init")
        .output_file(a.output, "--output")
        .output_file(a.plot, "--plot")
        .check(a.force);
    ParameterSettings usage_check = default_parameter_settings();
    apply_parameter_options(a, usage_check);  // before any data file is read
    FitRun run;
    for (const std::string& file : a.data)
        for (auto& d : load_emissivity_csv(file, a.wavelength_um))
            run.datasets.push_back(std::move(d));
    MicrofacetFitOptions options;
    options.starts = a.starts;
    options.seed = a.seed;
    options.quadrature.order = a.quadrature_order;
    options.scale_covariance_by_reduced_chi2 = a.scale_covariance;
    if (!a.init.empty()) apply_init(a.init, run.datasets.front().wavelength_um, options);
    apply_parameter_options(a, options.parameters);
    const MicrofacetFitProblem problem(run.datasets, options);
    run.result = problem.solve();
    run.datasets = problem.datasets();
    run.provenance = {a.data, utc_now_iso8601(), command_line(a)};
    run.output = a.output;
    run.plot = a.plot;
    const std::string name =
        a.name.empty() ? std::filesystem::path(a.output).stem().string() : a.name;
    write_file_atomic(a.output, fitted_material_yaml(name, run.result, run.provenance));
    if (!a.plot.empty())
        write_fit_plot(a.plot, run.datasets, run.result,
                       fmt::format("{}: polarized emissivity, measured and fitted", name),
                       options.quadrature);
    return run;
}

nlohmann::json fit_run_json(const FitRun& run) {
    nlohmann::json j = fit_report_json(run.result, run.datasets, run.provenance);
    j["material_file"] = run.output;
    j["plot_file"] = run.plot.empty() ? nlohmann::json(nullptr) : nlohmann::json(run.plot);
    return j;
}

std::string fit_run_text(const FitRun& run) {
    std::string text = fit_report_text(run.result, run.datasets);
    text += "material: " + run.output + "\n";
    if (!run.plot.empty()) text += "plot: " + run.plot + "\n";
    return text;
}

}  // namespace tirpol::fitting
