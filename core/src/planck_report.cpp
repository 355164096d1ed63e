#include <fmt/printf.h>

#include "tirpol/core/error.h"
#include "tirpol/core/limits.h"
#include "tirpol/core/path_info.h"

namespace tirpol {

PlanckAnswer evaluate_planck(const Band& band, const PlanckQuery& query) {
    if (query.temperature_k.has_value() == query.radiance_w_m2_sr.has_value())
        fail("planck: give one of a temperature or a band radiance");
    PlanckAnswer answer{query, 0.0, std::nullopt, std::nullopt};
    if (query.temperature_k) {
        double t = 0.0;
        try {
            t = check_temperature_k(*query.temperature_k, "--temperature-k");
        } catch (const Error& e) {
            throw OptionValueError("--temperature-k", e.what());
        }
        answer.radiance_w_m2_sr = check_finite(band.radiance(t), "band radiance");
        answer.radiance_dT_w_m2_sr_k =
            check_finite(band.radiance_dT(t), "band radiance derivative dL/dT");
        return answer;
    }
    const double l = *query.radiance_w_m2_sr;
    if (!(l > 0.0))
        throw OptionValueError(
            "--radiance",
            fmt::format("--radiance: expected a positive band radiance in W/(m²·sr), got {}", l));
    answer.radiance_w_m2_sr = l;
    answer.brightness_temperature_k =
        check_finite(band.brightness_temperature(l), "brightness temperature");
    return answer;
}

PlanckAnswer evaluate_planck(const PlanckQuery& query) {
    std::optional<SpectralResponse> rsr;
    if (!query.rsr.empty()) rsr = SpectralResponse::load_csv(query.rsr);
    std::optional<Band> band;
    try {
        band.emplace(query.band_um[0], query.band_um[1], rsr);
    } catch (const Error& e) {
        throw OptionValueError("--band-um", e.what());
    }
    return evaluate_planck(*band, query);
}

nlohmann::json planck_answer_json(const PlanckAnswer& a) {
    nlohmann::json out;
    out["band_um"] = a.query.band_um;
    out["rsr"] = a.query.rsr.empty() ? nlohmann::json(nullptr) : nlohmann::json(a.query.rsr);
    out["radiance_w_m2_sr"] = a.radiance_w_m2_sr;
    if (a.query.temperature_k) {
        out["temperature_k"] = *a.query.temperature_k;
        out["radiance_dT_w_m2_sr_k"] = *a.radiance_dT_w_m2_sr_k;
    } else {
        out["brightness_temperature_k"] = *a.brightness_temperature_k;
    }
    return out;
}

std::string planck_answer_text(const PlanckAnswer& a) {
    if (a.brightness_temperature_k)
        return fmt::sprintf("brightness temperature = %.4f K (%.4f °C)\n",
                            *a.brightness_temperature_k,
                            *a.brightness_temperature_k - kZeroCelsiusK);
    return fmt::sprintf("band %.4g–%.4g µm%s, T = %.3f K\n", a.query.band_um[0], a.query.band_um[1],
                        a.query.rsr.empty() ? "" : " with RSR " + a.query.rsr,
                        *a.query.temperature_k) +
           fmt::sprintf("band radiance  L    = %.6g W/(m²·sr)\n", a.radiance_w_m2_sr) +
           fmt::sprintf("derivative     dL/dT = %.6g W/(m²·sr·K)\n", *a.radiance_dT_w_m2_sr_k);
}

}  // namespace tirpol
