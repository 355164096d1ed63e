#include "tirpol/calibration/emissivity_extraction.h"

#include <fmt/ranges.h>

#include <cmath>

#include "tirpol/core/config.h"
#include "tirpol/core/emissivity_csv.h"
#include "tirpol/core/error.h"
#include "tirpol/core/limits.h"

namespace tirpol::calibration {

namespace {
PixelRect parse_rect(const ConfigNode& node) {
    const auto v = node.as<std::vector<double>>();
    const auto whole_in = [](double x, double lo) {
        return x == std::floor(x) && x >= lo && x <= limits::kMaxImageSide;
    };
    if (v.size() != 4 || !whole_in(v[0], 0) || !whole_in(v[1], 0) || !whole_in(v[2], 1) ||
        !whole_in(v[3], 1))
        node.fail(
            fmt::format("expected [x, y, width, height] in whole pixels (x, y ≥ 0; width, height ≥ "
                        "1; each ≤ {}), "
                        "found [{}]; a fractional rectangle would be truncated silently",
                        limits::kMaxImageSide, fmt::join(v, ", ")));
    return {static_cast<int>(v[0]), static_cast<int>(v[1]), static_cast<int>(v[2]),
            static_cast<int>(v[3])};
}
}  // namespace

EmissivityReflector EmissivityReflector::from_config(const ConfigNode& node) {
    node.check_keys({"rect", "emissivity", "emissivity_std", "temperature_k", "temperature_std_k"});
    EmissivityReflector r{parse_rect(node.at("rect"))};
    if (node.has("emissivity")) r.emissivity = node.get_in_range("emissivity", 0.0, 0.99);
    if (node.has("emissivity_std"))
        r.emissivity_std = node.get_in_range("emissivity_std", 0.0, 1.0);
    if (node.has("temperature_k"))
        r.temperature_k = node.get_in_range("temperature_k", 1.0, 2000.0);
    if (node.has("temperature_std_k"))
        r.temperature_std_k = node.get_in_range("temperature_std_k", 0.0, 100.0);
    if (r.emissivity > 0.0 && !r.temperature_k)
        node.fail(
            "an emissivity > 0 needs the reflector's temperature_k (its emission is removed)");
    return r;
}

EmissivityRois EmissivityRois::load(const std::string& path) {
    const ConfigNode root = ConfigNode::load_file(path);
    root.check_keys({"reflector", "targets"});
    EmissivityRois rois;
    rois.reflector = EmissivityReflector::from_config(root.at("reflector"));
    for (const ConfigNode& t : root.at("targets").elements()) {
        t.check_keys({"name", "rect", "view_angle_deg", "temperature_k", "temperature_std_k",
                      "blackbody_rect"});
        EmissivityTarget target;
        target.name = t.get<std::string>("name");
        target.rect = parse_rect(t.at("rect"));
        target.view_angle_deg = t.get_in_range("view_angle_deg", 0.0, 90.0);
        if (t.has("temperature_k"))
            target.temperature_k = t.get_in_range("temperature_k", 1.0, 2000.0);
        if (t.has("blackbody_rect")) target.blackbody_rect = parse_rect(t.at("blackbody_rect"));
        if (target.temperature_k.has_value() == target.blackbody_rect.has_value())
            t.fail(
                "expected exactly one of temperature_k (contact) or blackbody_rect (in-scene "
                "blackbody)");
        if (t.has("temperature_std_k"))
            target.temperature_std_k = t.get_in_range("temperature_std_k", 0.0, 100.0);
        rois.targets.push_back(target);
    }
    if (rois.targets.empty()) root.at("targets").fail("expected at least one target");
    return rois;
}

RegionMean downwelled_radiance(const Image& stokes, const EmissivityReflector& reflector,
                               const Band& band) {
    const double e = reflector.emissivity;
    if (!(e >= 0.0 && e < 1.0)) fail("reflector: emissivity {} is outside [0, 1)", e);
    if (e > 0.0 && !reflector.temperature_k)
        fail(
            "reflector: an emissivity of {} needs the reflector's temperature (its emission is "
            "removed)",
            e);
    RegionMean dw = region_mean(stokes, "S0", reflector.rect, "reflector");
    if (e == 0.0) return dw;
    // S0_r = (1 − ε_r)·L_dw + ε_r·L_BB(T_r) for a reflector in uniform surroundings (Kirchhoff).
    const double t = *reflector.temperature_k;
    const double l_r = band.radiance(t);
    const double s0 = dw.mean;
    dw.mean = (s0 - e * l_r) / (1.0 - e);
    dw.standard_error =
        std::hypot(dw.standard_error / (1.0 - e),
                   e * band.radiance_dT(t) * reflector.temperature_std_k / (1.0 - e),
                   (s0 - l_r) / ((1.0 - e) * (1.0 - e)) * reflector.emissivity_std);
    return dw;
}

std::vector<EmissivityResult> extract_emissivity(const Image& stokes, const EmissivityRois& rois,
                                                 const Band& band) {
    for (const char* c : {"S0", "S1", "S2"}) (void)stokes.channel(c);  // names the missing channel
    const RegionMean dw = downwelled_radiance(stokes, rois.reflector, band);
    std::vector<EmissivityResult> results;
    for (const auto& t : rois.targets) {
        EmissivityResult r;
        r.name = t.name;
        r.view_angle_deg = t.view_angle_deg;
        double sigma_lbb = 0.0;
        if (t.temperature_k) {
            r.temperature_k = *t.temperature_k;
            r.l_bb_w_m2_sr = band.radiance(*t.temperature_k);
            sigma_lbb = band.radiance_dT(*t.temperature_k) * t.temperature_std_k;
        } else {
            const RegionMean bb =
                region_mean(stokes, "S0", *t.blackbody_rect, t.name + " blackbody_rect");
            r.l_bb_w_m2_sr = bb.mean;
            sigma_lbb = bb.standard_error;
            r.temperature_k = band.brightness_temperature(bb.mean);
        }
        r.l_dw_w_m2_sr = dw.mean;
        const double d = r.l_bb_w_m2_sr - r.l_dw_w_m2_sr;
        if (!(d > 0.0))
            fail(
                "target '{}': L_BB = {:.4g} W/(m²·sr) does not exceed the downwelled L_dw = "
                "{:.4g}; eq 17 needs the "
                "target warmer (in band) than its reflected background",
                t.name, r.l_bb_w_m2_sr, r.l_dw_w_m2_sr);
        const RegionMean s0 = region_mean(stokes, "S0", t.rect, t.name);
        const RegionMean s1 = region_mean(stokes, "S1", t.rect, t.name);
        const RegionMean s2 = region_mean(stokes, "S2", t.rect, t.name);
        r.pixels = s0.n;
        const double sd = dw.standard_error;
        r.eps_s0 = (s0.mean - r.l_dw_w_m2_sr) / d;
        // First-order propagation: ∂ε0/∂S0 = 1/D, ∂ε0/∂L_dw = (S0 − L_BB)/D², ∂ε0/∂L_BB = −ε0/D.
        r.eps_s0_std = std::sqrt(std::pow(s0.standard_error / d, 2) +
                                 std::pow((s0.mean - r.l_bb_w_m2_sr) / (d * d) * sd, 2) +
                                 std::pow(r.eps_s0 / d * sigma_lbb, 2));
        auto polarized = [&](const RegionMean& s, double& eps, double& std) {
            eps = s.mean / d;
            std = std::sqrt(std::pow(s.standard_error / d, 2) + std::pow(eps / d * sd, 2) +
                            std::pow(eps / d * sigma_lbb, 2));
        };
        polarized(s1, r.eps_s1, r.eps_s1_std);
        polarized(s2, r.eps_s2, r.eps_s2_std);
        for (double v : {r.eps_s0, r.eps_s0_std, r.eps_s1, r.eps_s1_std, r.eps_s2, r.eps_s2_std})
            check_finite(v, "target '" + t.name + "': emissivity");
        constexpr double tol = limits::kEmissivityTolerance;
        if (r.eps_s0 < -tol || r.eps_s0 > 1.0 + tol)
            r.warnings.push_back(
                fmt::format("target '{}': ε_S0 = {:.3f} is outside [0, 1] beyond measurement noise "
                            "(±{}): check its temperature "
                            "({:.2f} K), its rectangle and the reflector's; `fit` refuses this row",
                            t.name, r.eps_s0, tol, r.temperature_k));
        results.push_back(r);
    }
    return results;
}

std::string emissivity_csv(const std::vector<EmissivityResult>& results) {
    std::vector<EmissivityCsvRow> rows;
    for (const auto& r : results)
        rows.push_back({r.name, r.view_angle_deg, r.temperature_k, r.pixels, r.l_dw_w_m2_sr,
                        r.l_bb_w_m2_sr, EmissivityFrame::Image, r.eps_s0, r.eps_s0_std, r.eps_s1,
                        r.eps_s1_std, r.eps_s2, r.eps_s2_std, std::nullopt, 0});
    return emissivity_csv_text(rows);
}

}  // namespace tirpol::calibration
