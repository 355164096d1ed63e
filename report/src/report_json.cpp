#include <nlohmann/json.hpp>

#include "tirpol/core/utf8.h"
#include "tirpol/report/comparison_report.h"

namespace tirpol::report {

namespace {

nlohmann::json optional_number(const std::optional<double>& v) { return v ? nlohmann::json(*v) : nlohmann::json(nullptr); }

nlohmann::json to_json(const QuantityStats& s) {
    return {{"pixel_count", s.pixel_count},   {"measured_mean", s.measured_mean}, {"measured_std", s.measured_std},
            {"simulated_mean", s.simulated_mean}, {"simulated_std", s.simulated_std}, {"bias", s.bias},
            {"rmse", s.rmse}};
}

nlohmann::json to_json(const ZStats& z) {
    return {{"pixel_count", z.pixel_count}, {"fraction_above_2", z.fraction_above_2},
            {"fraction_above_3", z.fraction_above_3}, {"mean", z.mean}, {"rms", z.rms},
            {"consistent_with_noise", consistent_with_noise(z)}};
}

}  // namespace

std::string comparison_json(const CompareResult& r) {
    nlohmann::json j;
    j["measured"] = {{"width", r.width}, {"height", r.height}};
    j["simulated"] = {{"width", r.simulated_width}, {"height", r.simulated_height}};
    j["units"] = r.units;
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
                         {"note", g.note}};
    for (const auto& [q, s] : r.noise)
        j["noise"][q] = {{"measured_source", s.measured},
                         {"simulated_source", s.simulated},
                         {"measured_sigma_median", s.measured_sigma_median},
                         {"simulated_sigma_median", s.simulated_sigma_median}};
    j["background"] = r.background.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.background);
    j["expected_fraction_above_2"] = kNormalTailAbove2;
    j["expected_fraction_above_3"] = kNormalTailAbove3;
    j["regions"] = nlohmann::json::array();
    for (const auto& region : r.regions) {
        nlohmann::json jr{{"name", region.name}, {"pixel_count", region.pixel_count}};
        for (const auto& [q, s] : region.stats) jr["stats"][q] = to_json(s);
        if (region.s1_contrast_measured && region.s1_contrast_simulated)
            jr["s1_contrast"] = {{"measured", *region.s1_contrast_measured},
                                 {"simulated", *region.s1_contrast_simulated},
                                 {"difference", *region.s1_contrast_measured - *region.s1_contrast_simulated}};
        else
            jr["s1_contrast"] = nullptr;
        for (const auto& [q, z] : region.z) jr["z"][q] = to_json(z);
        j["regions"].push_back(std::move(jr));
    }
    for (const auto& [name, range] : r.colour_scales) j["colour_scales"][name] = range;
    j["notes"] = r.notes;
    nlohmann::json pngs = nlohmann::json::array();
    for (const auto& p : r.pngs) pngs.push_back(p.filename().string());
    j["files"] = {{"html", r.html.filename().string()},
                  {"json", r.json.filename().string()},
                  {"exr", r.exr.filename().string()},
                  {"pngs", pngs}};
    return json_text(j, 2) + "\n";
}

}  // namespace tirpol::report
