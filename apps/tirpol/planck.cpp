// `tirpol planck`: band radiance and dL/dT of a blackbody, or brightness temperature of a radiance.

#include "cli.h"
#include "common_options.h"
#include "tirpol/core/path_info.h"

namespace tirpol::cli {

namespace {
struct PlanckArgs {
    PlanckQuery query;
    std::vector<double> band_um;
    bool json = false;
};

void run_planck(PlanckArgs& a) {
    a.query.band_um = {a.band_um[0], a.band_um[1]};
    const PlanckAnswer answer = evaluate_planck(a.query);
    a.json ? print_json(planck_answer_json(answer)) : print_text(planck_answer_text(answer));
}

void register_planck(CLI::App& app) {
    auto args = std::make_shared<PlanckArgs>();
    auto* cmd = app.add_subcommand("planck",
                                   "Blackbody band radiance and dL/dT, or brightness temperature");
    auto* t = cmd->add_option("--temperature-k", args->query.temperature_k,
                              "Blackbody temperature in kelvin");
    auto* l = cmd->add_option("--radiance", args->query.radiance_w_m2_sr,
                              "Band radiance in W/(m²·sr) → brightness temperature");
    t->excludes(l);
    add_band_options(cmd, args->band_um, args->query.rsr)->required();
    add_json_flag(cmd, args->json, "Print JSON (keys in docs/cli.md)");
    cmd->callback([args, t, l] {
        if (t->count() == 0 && l->count() == 0)
            throw CLI::RequiredError("one of --temperature-k or --radiance");
        run_planck(*args);
    });
}
}  // namespace

TIRPOL_REGISTER_COMMAND(20, register_planck);

}  // namespace tirpol::cli
