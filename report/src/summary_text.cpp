#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "tirpol/report/comparison_report.h"

namespace tirpol::report {

namespace {

std::string join_names(const std::vector<std::string>& names) {
    std::string out;
    for (std::size_t i = 0; i < names.size(); ++i)
        out += (i == 0 ? "" : i + 1 == names.size() ? " and " : ", ") + names[i];
    return out;
}

// "S1 by −0.12 (4.1 σ; detectable 0.09)" for each quantity of `region` that exceeds the noise.
std::string exceeding_quantities(const RegionResult& region, const std::string& units) {
    std::vector<std::string> parts;
    for (const Quantity q : kZQuantities) {
        const auto& t = region.verdicts[q].mean;
        if (t.verdict != Agreement::ExceedsNoise) continue;
        parts.push_back(fmt::format("{} by {:+.3g} {} ({:.1f} σ of the region mean)",
                                    quantity_name(q), t.difference, units, t.t));
    }
    return join_names(parts);
}

std::string calibration_sentence(const CompareResult& r) {
    if (!r.calibration_range)
        return "The measured image does not state its radiometric calibration range, so "
               "extrapolation beyond the blackbody set-points cannot be checked. ";
    const auto& c = *r.calibration_range;
    if (c.outside_fraction <= 0.0)
        return fmt::format(
            "Every measured pixel lies inside the blackbody calibration range ({:.1f}–{:.1f} K). ",
            c.lo_k, c.hi_k);
    const double pixels = static_cast<double>(r.width) * static_cast<double>(r.height);
    return fmt::format(
        "{:.1f} % of the measured pixels (about {:.0f} of {:.0f}) lie outside the blackbody "
        "calibration range ({:.1f}–{:.1f} K): their radiances are extrapolated from the "
        "calibration, an error no σ here contains, so a difference there may be the "
        "calibration's. ",
        100.0 * c.outside_fraction, std::round(c.outside_fraction * pixels), pixels, c.lo_k,
        c.hi_k);
}

// The three parts of each region mean's σ, in words.
std::string sigma_parts_sentence(const CompareResult& r) {
    const auto& shift = r.registration.residual_shift_px;
    return fmt::format(
        "Each region mean's σ has three parts: the measurement's ({}); the render's ({}); and the "
        "registration's (the residual misalignment of {:.2g} px times the region's mean "
        "gradient). ",
        r.measured_sigma_contains, r.simulated_sigma_contains, std::hypot(shift[0], shift[1]));
}

std::string power_sentence(const CompareResult& r) {
    std::string ranges;
    std::vector<std::string> powerless;
    std::size_t tested = 0;
    for (const Quantity quantity : kZQuantities) {
        const std::string& q = quantity_name(quantity);
        double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
        for (const auto& region : r.regions) {
            const auto& t = region.verdicts[quantity].mean;
            if (t.verdict == Agreement::NoData) continue;
            ++tested;
            lo = std::min(lo, t.detectable_bias);
            hi = std::max(hi, t.detectable_bias);
            if (!verdict_has_power(region, quantity)) powerless.push_back(region.name + " " + q);
        }
        if (hi <= 0.0) continue;
        const std::string lo_text = fmt::format("{:.2g}", lo), hi_text = fmt::format("{:.2g}", hi);
        ranges += fmt::format("{}{} {}", ranges.empty() ? "" : ", ", q,
                              lo_text == hi_text ? lo_text : lo_text + "–" + hi_text);
    }
    if (tested == 0) return "";
    std::string out = fmt::format(
        "With {:.0f} % false alarms per region ({:.1f} % per quantity) and {:.0f} % power, the "
        "smallest region-mean bias the tests detect is {} {}; a smaller real difference would "
        "read \"consistent with noise\". ",
        100.0 * r.design.false_alarm_per_region, 100.0 * r.design.false_alarm_per_quantity(),
        100.0 * r.design.power, ranges, r.units);
    if (powerless.empty())
        return out +
               "The verdicts have power: every detectable bias is smaller than the simulated "
               "value it tests. ";
    out += powerless.size() == tested ? "None of the verdicts has power: " : "No power in ";
    out += join_names(powerless) +
           ": there the detectable bias is at least the simulated value itself, so a simulation "
           "of zero would read \"consistent with noise\" too, and that verdict says little. ";
    return out;
}

std::string sigma_diagnostic_sentence(const CompareResult& r) {
    std::vector<std::string> over, under;
    for (const auto& region : r.regions)
        for (const Quantity quantity : kZQuantities) {
            const std::string& q = quantity_name(quantity);
            const auto check = region.verdicts[quantity].sigma.verdict;
            if (check == SigmaCheck::Overestimated) over.push_back(region.name + " " + q);
            if (check == SigmaCheck::Underestimated) under.push_back(region.name + " " + q);
        }
    std::string out;
    if (!over.empty())
        out += "Per-pixel σ overestimated (z scatters less than 1) in " + join_names(over) +
               ": the per-pixel check is blunt there; the region-mean verdicts are conservative. ";
    if (!under.empty())
        out += "Per-pixel σ underestimated, or the difference varies within the region, in " +
               join_names(under) + ". ";
    if (over.empty() && under.empty())
        out += "The per-pixel σ is plausible in every region (z scatters as N(0, 1)). ";
    return out;
}

}  // namespace

bool verdict_has_power(const RegionResult& region, Quantity quantity) {
    if (quantity == Quantity::DoLP) return false;
    const auto& t = region.verdicts[quantity].mean;
    return t.verdict != Agreement::NoData && std::isfinite(t.detectable_bias) &&
           t.detectable_bias < std::abs(region.stats[quantity].simulated_mean);
}

std::string summary_paragraph(const CompareResult& r) {
    std::vector<std::string> agree, no_data;
    std::vector<const RegionResult*> exceed;
    for (const auto& region : r.regions) {
        if (region.verdict == Agreement::ConsistentWithNoise) agree.push_back(region.name);
        if (region.verdict == Agreement::NoData) no_data.push_back(region.name);
        if (region.verdict == Agreement::ExceedsNoise) exceed.push_back(&region);
    }
    std::string out;
    if (exceed.empty())
        out += fmt::format("All {} regions agree with the simulation within the noise{}. ",
                           agree.size(), agree.empty() ? "" : " (" + join_names(agree) + ")");
    else {
        out += fmt::format("{} of {} regions differ from the simulation by more than the noise: ",
                           exceed.size(), r.regions.size());
        for (std::size_t i = 0; i < exceed.size(); ++i)
            out += (i ? "; " : "") + exceed[i]->name + " in " +
                   exceeding_quantities(*exceed[i], r.units);
        out +=
            ". There the scene and its model differ (material, temperature, geometry) or the "
            "measurement has an error its σ does not hold (calibration). ";
        if (!agree.empty()) out += "Within the noise: " + join_names(agree) + ". ";
    }
    if (!no_data.empty()) out += "No data in " + join_names(no_data) + ". ";
    out += calibration_sentence(r);
    out += sigma_parts_sentence(r);
    out += power_sentence(r);
    out += sigma_diagnostic_sentence(r);
    if (!out.empty() && out.back() == ' ') out.pop_back();
    return out;
}

}  // namespace tirpol::report
