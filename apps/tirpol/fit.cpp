// `tirpol fit`: micro-facet pBRDF parameters from measured polarized emissivity (docs/fitting.md).

#include "cli.h"
#include "common_options.h"
#include "tirpol/fitting/fit_run.h"

namespace tirpol::cli {

namespace {
struct FitArgs {
    fitting::FitRunOptions options;
    std::string model = "micro-facet";
    bool json = false;
};

void run_fit(const FitArgs& a) {
    if (a.model != "micro-facet" && a.model != "microfacet")
        usage_error("--model",
                    "{}: only the micro-facet model can be fitted (expected micro-facet)", a.model);
    const fitting::FitRun run = fitting::run_fit(a.options);
    a.json ? print_json(fitting::fit_run_json(run)) : print_text(fitting::fit_run_text(run));
    if (!run.result.usable)
        fail("the fit did not converge to a usable solution ({})", run.result.termination);
}

void register_fit(CLI::App& app) {
    auto args = std::make_shared<FitArgs>();
    auto& o = args->options;
    auto* cmd = app.add_subcommand(
        "fit", "Fit micro-facet pBRDF parameters to measured polarized emissivity");
    add_required_input(cmd, "data", o.data,
                       "Emissivity CSV(s) from `tirpol extract-emissivity` (docs/fitting.md)");
    cmd->add_option("--model", args->model, "Model to fit (micro-facet)")->capture_default_str();
    cmd->add_option("--fix", o.fix,
                    "Hold parameters fixed: NAME[=VALUE],... (n k sigma bias tau_deg omega_deg "
                    "rho_d rho_v)")
        ->delimiter(',');
    cmd->add_option("--free", o.free, "Free parameters that are fixed by default: NAME,...")
        ->delimiter(',');
    cmd->add_option("--bound", o.bounds, "Bounds: NAME=LOWER:UPPER,...")->delimiter(',');
    cmd->add_option(
        "--init", o.init,
        "Material YAML or library name whose micro-facet parameters are the first start");
    cmd->add_option("--starts", o.starts, "Number of starts (initial + Latin hypercube)")
        ->capture_default_str();
    cmd->add_option("--seed", o.seed, "Seed of the Latin hypercube")->capture_default_str();
    cmd->add_option("--quadrature-order", o.quadrature_order, "Gauss–Legendre nodes per panel")
        ->capture_default_str();
    cmd->add_option("--wavelength-um", o.wavelength_um,
                    "Effective wavelength of data without a wavelength_um column")
        ->capture_default_str();
    cmd->add_flag(
        "--scale-covariance", o.scale_covariance,
        "Scale the covariance by chi2/dof (when the stated uncertainties are not trusted)");
    add_output_option(cmd, o.output, "Fitted material YAML");
    cmd->add_option("--name", o.name, "Material name (default: the output file's stem)");
    cmd->add_option("--plot", o.plot, "PNG plot of data and fit (like the paper's Fig. 1)");
    add_json_flag(cmd, args->json, "Print the fit report as JSON (keys in docs/fitting.md)");
    add_force_flag(cmd, o.force);
    cmd->callback([args] { run_fit(*args); });
}
}  // namespace

TIRPOL_REGISTER_COMMAND(600, register_fit);

}  // namespace tirpol::cli
