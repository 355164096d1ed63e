// `tirpol planck`: band radiance and dL/dT of a blackbody, or brightness temperature of a radiance.

#include <cstdio>
#include <nlohmann/json.hpp>
#include <optional>

#include "cli.h"
#include "tirpol/core/checks.h"
#include "tirpol/core/error.h"
#include "tirpol/core/radiometry.h"
#include "tirpol/core/utf8.h"

namespace tirpol::cli {

namespace {
struct PlanckArgs {
    std::optional<double> temperature_k;
    std::optional<double> radiance;
    std::vector<double> band_um;
    std::string rsr;
    bool json = false;
};

void run_planck(const PlanckArgs& a) {
    std::optional<SpectralResponse> rsr;
    if (!a.rsr.empty()) rsr = SpectralResponse::load_csv(a.rsr);
    const Band band =
        parse_option_value("--band-um", [&] { return Band(a.band_um[0], a.band_um[1], rsr); });
    nlohmann::json out;
    out["band_um"] = {a.band_um[0], a.band_um[1]};
    out["rsr"] = a.rsr.empty() ? nlohmann::json(nullptr) : nlohmann::json(a.rsr);
    if (a.temperature_k) {
        const double t = parse_option_value("--temperature-k", [&] {
            return check_temperature_k(*a.temperature_k, "--temperature-k");
        });
        const double radiance = check_finite(band.radiance(t), "band radiance");
        const double radiance_dT =
            check_finite(band.radiance_dT(t), "band radiance derivative dL/dT");
        out["temperature_k"] = t;
        out["radiance_w_m2_sr"] = radiance;
        out["radiance_dT_w_m2_sr_k"] = radiance_dT;
        if (!a.json) {
            std::printf("band %.4g–%.4g µm%s, T = %.3f K\n", a.band_um[0], a.band_um[1],
                        a.rsr.empty() ? "" : (" with RSR " + a.rsr).c_str(), t);
            std::printf("band radiance  L    = %.6g W/(m²·sr)\n", radiance);
            std::printf("derivative     dL/dT = %.6g W/(m²·sr·K)\n", radiance_dT);
        }
    } else {
        const double l = *a.radiance;
        if (!(l > 0.0))
            usage_error("--radiance", "expected a positive band radiance in W/(m²·sr), got {}", l);
        const double t = check_finite(band.brightness_temperature(l), "brightness temperature");
        out["radiance_w_m2_sr"] = l;
        out["brightness_temperature_k"] = t;
        if (!a.json)
            std::printf("brightness temperature = %.4f K (%.4f °C)\n", t, t - kZeroCelsiusK);
    }
    if (a.json) std::printf("%s\n", json_text(out, 2).c_str());
}
}  // namespace

namespace {
void register_planck(CLI::App& app) {
    auto args = std::make_shared<PlanckArgs>();
    auto* cmd = app.add_subcommand("planck",
                                   "Blackbody band radiance and dL/dT, or brightness temperature");
    auto* t =
        cmd->add_option("--temperature-k", args->temperature_k, "Blackbody temperature in kelvin");
    auto* l = cmd->add_option("--radiance", args->radiance,
                              "Band radiance in W/(m²·sr) → brightness temperature");
    t->excludes(l);
    cmd->add_option("--band-um", args->band_um, "Band limits LO HI in micrometres")
        ->required()
        ->expected(2);
    cmd->add_option("--rsr", args->rsr, "Relative spectral response CSV (wavelength_um,response)")
        ->check(CLI::ExistingFile);
    cmd->add_flag("--json", args->json, "Print JSON (keys in docs/cli.md)");
    cmd->callback([args, t, l] {
        if (t->count() == 0 && l->count() == 0)
            throw CLI::RequiredError("one of --temperature-k or --radiance");
        run_planck(*args);
    });
}

}  // namespace

TIRPOL_REGISTER_COMMAND(20, register_planck);

}  // namespace tirpol::cli
