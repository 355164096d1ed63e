#include <cmath>
#include <nlohmann/json.hpp>

#include "tirpol/core/utf8.h"
#include "tirpol/report/comparison_report.h"

namespace tirpol::report {

namespace {

nlohmann::json optional_number(const std::optional<double>& v) {
    return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
}

/// Degrees of freedom; null for infinite (a variance taken as exact): JSON has no infinity.
nlohmann::json degrees_of_freedom(double dof) {
    return std::isfinite(dof) ? nlohmann::json(dof) : nlohmann::json(nullptr);
}

nlohmann::json to_json(const QuantityStats& s) {
    return {{"pixel_count", s.pixel_count},
            {"measured_mean", s.measured_mean},
            {"measured_std", s.measured_std},
            {"simulated_mean", s.simulated_mean},
            {"simulated_std", s.simulated_std},
            {"bias", s.bias},
            {"rmse", s.rmse},
            {"bias_sigma", s.bias_sigma}};
}

nlohmann::json to_json(const ZStats& z) {
    return {{"pixel_count", z.pixel_count},
            {"fraction_above_2", z.fraction_above_2},
            {"fraction_above_3", z.fraction_above_3},
            {"mean", z.mean},
            {"rms", z.rms}};
}

nlohmann::json to_json(const UncertaintyComponent& u) {
    return {{"sigma", u.sigma}, {"dof", degrees_of_freedom(u.dof)}};
}

nlohmann::json to_json(const QuantityVerdict& v) {
    const auto& t = v.mean;
    const auto& d = v.sigma;
    return {{"verdict", to_string(t.verdict)},
            {"mean_difference", t.difference},
            {"pixel_count", t.pixel_count},
            {"sigma_mean", to_json(t.combined)},
            {"sigma_measured_independent", to_json(t.measured_independent)},
            {"sigma_measured_common", to_json(t.measured_common)},
            {"sigma_simulated", to_json(t.simulated)},
            {"sigma_registration", to_json(t.registration)},
            {"t", t.t},
            {"p_value", t.p_value},
            {"critical_t", t.critical_t},
            {"false_alarm", t.false_alarm},
            {"power", t.power},
            {"detectable_bias", t.detectable_bias},
            {"sigma_check", to_string(d.verdict)},
            {"z_variance", d.z_variance},
            {"z_variance_sigma", d.z_variance_sigma},
            {"sigma_factor", d.sigma_factor}};
}

nlohmann::json to_json(const AopStats& a) {
    if (a.pixel_count == 0)
        return {{"region_pixel_count", a.region_pixel_count},
                {"pixel_count", 0},
                {"measured_mean_deg", nullptr},
                {"simulated_mean_deg", nullptr},
                {"difference_mean_deg", nullptr},
                {"difference_std_deg", nullptr}};
    return {{"region_pixel_count", a.region_pixel_count},
            {"pixel_count", a.pixel_count},
            {"measured_mean_deg", a.measured_mean_deg},
            {"simulated_mean_deg", a.simulated_mean_deg},
            {"difference_mean_deg", a.difference_mean_deg},
            {"difference_std_deg", a.difference_std_deg}};
}

nlohmann::json to_json(const Provenance& p) {
    nlohmann::json inputs = nlohmann::json::array();
    for (const auto& f : p.inputs) {
        nlohmann::json attributes = nlohmann::json::object();
        for (const auto& [name, value] : f.attributes) attributes[name] = value;
        inputs.push_back({{"role", f.role},
                          {"path", f.path.string()},
                          {"sha256", f.sha256},
                          {"size_bytes", f.size_bytes},
                          {"attributes", attributes}});
    }
    return {{"tool_version", p.tool_version},
            {"build_commit", p.build_commit},
            {"command_line", p.command_line},
            {"inputs", inputs}};
}

}  // namespace

std::string comparison_json(const CompareResult& r) {
    nlohmann::json j;
    j["measured"] = {{"width", r.width}, {"height", r.height}};
    j["simulated"] = {{"width", r.simulated_width}, {"height", r.simulated_height}};
    j["units"] = r.units;
    j["provenance"] = to_json(r.provenance);
    j["band_um"] = r.band_um ? nlohmann::json(*r.band_um) : nlohmann::json(nullptr);
    j["band_source"] = r.band_source;
    const auto& g = r.registration;
    const double residual = std::hypot(g.residual_shift_px[0], g.residual_shift_px[1]);
    j["registration"] = {{"method", to_string(g.method)},
                         {"model", g.model},
                         {"measured_to_simulated", g.measured_to_simulated},
                         {"control_point_rms_px", optional_number(g.control_point_rms_px)},
                         {"ecc_correlation", optional_number(g.ecc_correlation)},
                         {"residual_shift_px", g.residual_shift_px},
                         {"residual_misalignment_px", residual},
                         {"max_corner_displacement_px", g.max_corner_displacement_px},
                         {"rotation_deg", g.rotation_deg},
                         {"identity_edge_mismatch", optional_number(g.identity_edge_mismatch)},
                         {"registered_edge_mismatch", optional_number(g.registered_edge_mismatch)},
                         {"note", g.note}};
    for (const Quantity q : kZQuantities) {
        const NoiseSource& s = r.noise[q];
        j["noise"][quantity_name(q)] = {{"measured_source", s.measured},
                                        {"simulated_source", s.simulated},
                                        {"measured_sigma_median", s.measured_sigma_median},
                                        {"simulated_sigma_median", s.simulated_sigma_median},
                                        {"measured_dof", degrees_of_freedom(s.measured_dof)},
                                        {"simulated_dof", degrees_of_freedom(s.simulated_dof)},
                                        {"measured_shared", s.measured_shared}};
    }
    j["summary"] = summary_paragraph(r);
    j["design"] = {{"false_alarm_per_region", r.design.false_alarm_per_region},
                   {"false_alarm_per_quantity", r.design.false_alarm_per_quantity()},
                   {"power", r.design.power}};
    j["sigma_contains"] = {
        {"measured", r.measured_sigma_contains},
        {"simulated", r.simulated_sigma_contains},
        {"registration",
         "the residual misalignment times the region's mean gradient of the simulated quantity"}};
    if (const auto& c = r.calibration_range)
        j["calibration_range"] = {{"outside_fraction", c->outside_fraction},
                                  {"range_k", {c->lo_k, c->hi_k}}};
    else
        j["calibration_range"] = nullptr;
    j["background"] = r.background.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.background);
    j["expected_fraction_above_2"] = kNormalTailAbove2;
    j["expected_fraction_above_3"] = kNormalTailAbove3;
    j["regions"] = nlohmann::json::array();
    for (const auto& region : r.regions) {
        nlohmann::json jr{{"name", region.name}, {"pixel_count", region.pixel_count}};
        for (const Quantity q : kComparedQuantities)
            jr["stats"][quantity_name(q)] = to_json(region.stats[q]);
        if (region.s1_contrast_measured && region.s1_contrast_simulated)
            jr["s1_contrast"] = {
                {"measured", *region.s1_contrast_measured},
                {"simulated", *region.s1_contrast_simulated},
                {"difference", *region.s1_contrast_measured - *region.s1_contrast_simulated}};
        else
            jr["s1_contrast"] = nullptr;
        for (const Quantity q : kZQuantities) {
            jr["z"][quantity_name(q)] = to_json(region.z[q]);
            jr["verdicts"][quantity_name(q)] = to_json(region.verdicts[q]);
        }
        jr["z"]["all"] = to_json(region.z_pooled);
        jr["verdict"] = to_string(region.verdict);
        jr["aop"] = to_json(region.aop);
        if (const auto& k = region.s0_bias_k)
            jr["s0_bias_k"] = {{"temperature_k", k->temperature_k},
                               {"radiance_dT_w_m2_sr_k", k->radiance_dT},
                               {"bias_k", k->bias_k},
                               {"bias_sigma_k", k->bias_sigma_k}};
        else
            jr["s0_bias_k"] = nullptr;
        j["regions"].push_back(std::move(jr));
    }
    for (const auto& [name, range] : r.colour_scales) j["colour_scales"][name] = range;
    j["notes"] = r.notes;
    nlohmann::json pngs = nlohmann::json::array();
    for (const auto& p : r.pngs) pngs.push_back(p.filename().string());
    nlohmann::json svgs = nlohmann::json::array();
    for (const auto& p : r.svgs) svgs.push_back(p.filename().string());
    j["files"] = {{"html", r.html.filename().string()},
                  {"json", r.json.filename().string()},
                  {"exr", r.exr.filename().string()},
                  {"pngs", pngs},
                  {"svgs", svgs}};
    return json_text(j, 2) + "\n";
}

}  // namespace tirpol::report
