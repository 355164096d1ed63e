#include "tirpol/calibration/polarimetric_file.h"

#include <cmath>
#include <filesystem>
#include <sstream>

#include "tirpol/core/atomic_file.h"
#include "tirpol/core/config.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/stokes.h"

namespace tirpol::calibration {

namespace {
// YAML double-quoted scalar (the strings we write are paths and ISO dates).
std::string quoted(const std::string& s) {
    std::string out = "\"";
    for (char c : s) {
        if (c == '"' || c == '\\') out += '\\';
        out += c;
    }
    return out + "\"";
}
}  // namespace

std::string polarimetric_maps_path(const std::string& yaml_path) {
    std::filesystem::path p(yaml_path);
    return (p.parent_path() / (p.stem().string() + ".maps.exr")).string();
}

void write_polarimetric_calibration(const std::string& yaml_path,
                                    const PolarimetricCalibration& cal) {
    Image maps(cal.wire_grid.width, cal.wire_grid.height);
    for (const auto& p : cal.wire_grid.positions) {
        maps.set_channel("tau_" + polarizer_angle_tag(p.angle_deg), p.tau);
        maps.set_channel("B_" + polarizer_angle_tag(p.angle_deg), p.background);
        maps.set_channel("residual_" + polarizer_angle_tag(p.angle_deg), p.residual_rms);
        if (p.has_covariance()) {
            maps.set_channel("tau_var_" + polarizer_angle_tag(p.angle_deg), p.tau_var);
            maps.set_channel("B_var_" + polarizer_angle_tag(p.angle_deg), p.background_var);
            maps.set_channel("tau_B_cov_" + polarizer_angle_tag(p.angle_deg), p.tau_background_cov);
        }
    }
    maps.attributes()["tirpol_calibration"] = std::string("polarimetric-maps");
    maps.attributes()["units_B"] = std::string("W/(m^2 sr)");
    maps.attributes()["units_tau"] = std::string("1");
    const std::string maps_path = polarimetric_maps_path(yaml_path);
    write_exr(maps_path, maps);

    std::ostringstream y;
    y.precision(10);
    y << "# tirpol polarimetric calibration (docs/calibration.md)\n"
      << "tirpol_calibration: polarimetric\n"
      << "created_utc: " << quoted(cal.created_utc) << "\n"
      << "session: " << quoted(cal.session) << "\n"
      << "radiometric_calibration: " << quoted(cal.radiometric_calibration) << "\n"
      << "maps: " << quoted(std::filesystem::path(maps_path).filename().string()) << "\n";
    if (cal.band_known()) y << "band_um: [" << cal.band_lo_um << ", " << cal.band_hi_um << "]\n";
    y << "analyzer:\n  method: " << quoted(cal.analyzer_method) << "\n  positions:\n";
    for (const auto& p : cal.analyzer.positions) {
        const double er = p.extinction_ratio();
        y << "    - nominal_angle_deg: " << p.nominal_angle_deg << "\n"
          << "      axis_angle_deg: " << p.axis_angle_deg << "\n"
          << "      diattenuation: " << p.diattenuation << "\n"
          << "      extinction_ratio: "
          << (std::isfinite(er) ? fmt::format("{:.6g}", er) : std::string(".inf")) << "\n"
          << "      relative_transmission: " << p.relative_transmission << "\n"
          << "      background: " << p.background << "\n";
    }
    write_file_atomic(yaml_path, y.str());
}

void check_same_band(const RadiometricCalibration& radiometric, const std::string& radiometric_name,
                     const PolarimetricCalibration& polarimetric,
                     const std::string& polarimetric_name) {
    if (!polarimetric.band_known()) return;
    if (std::abs(polarimetric.band_lo_um - radiometric.band_lo_um) <= 1e-6 &&
        std::abs(polarimetric.band_hi_um - radiometric.band_hi_um) <= 1e-6)
        return;
    fail(
        "{} is a polarimetric calibration for {:g}–{:g} µm (made with {}) but the radiometric "
        "calibration {} is "
        "for {:g}–{:g} µm; its wire-grid τ and B maps hold only in their own band: make the "
        "polarimetric "
        "calibration again with this radiometric calibration",
        polarimetric_name, polarimetric.band_lo_um, polarimetric.band_hi_um,
        polarimetric.radiometric_calibration.empty() ? "an unnamed radiometric calibration"
                                                     : polarimetric.radiometric_calibration,
        radiometric_name, radiometric.band_lo_um, radiometric.band_hi_um);
}

PolarimetricCalibration read_polarimetric_calibration(const std::string& yaml_path) {
    const ConfigNode root = ConfigNode::load_file(yaml_path);
    root.check_keys({"tirpol_calibration", "created_utc", "session", "radiometric_calibration",
                     "maps", "band_um", "analyzer"});
    if (root.get<std::string>("tirpol_calibration") != "polarimetric")
        root.at("tirpol_calibration").fail("expected 'polarimetric'");
    PolarimetricCalibration cal;
    cal.created_utc = root.get<std::string>("created_utc");
    cal.session = root.get<std::string>("session");
    cal.radiometric_calibration = root.get<std::string>("radiometric_calibration");
    if (root.has("band_um")) {
        const auto band = root.get<std::vector<double>>("band_um");
        if (band.size() != 2 || !(band[0] > 0.0) || !(band[1] > band[0]) || !std::isfinite(band[1]))
            root.at("band_um").fail("expected [LO, HI] in micrometres with 0 < LO < HI");
        cal.band_lo_um = band[0];
        cal.band_hi_um = band[1];
    }
    const ConfigNode analyzer = root.at("analyzer");
    analyzer.check_keys({"method", "positions"});
    cal.analyzer_method = analyzer.get<std::string>("method");
    for (const ConfigNode& p : analyzer.at("positions").elements()) {
        p.check_keys({"nominal_angle_deg", "axis_angle_deg", "diattenuation", "extinction_ratio",
                      "relative_transmission", "background"});
        AnalyzerPosition pos;
        pos.nominal_angle_deg = p.get<double>("nominal_angle_deg");
        pos.axis_angle_deg = p.get<double>("axis_angle_deg");
        pos.diattenuation = p.get_in_range("diattenuation", 0.0, 1.0);
        pos.relative_transmission = p.get_in_range("relative_transmission", 1e-6, 10.0);
        pos.background = p.get<double>("background");
        cal.analyzer.positions.push_back(pos);
    }
    const std::string maps_path = root.resolve_path(root.get<std::string>("maps")).string();
    const Image maps = read_exr(maps_path);
    cal.wire_grid.width = maps.width();
    cal.wire_grid.height = maps.height();
    for (const auto& p : cal.analyzer.positions) {
        const std::string tag = polarizer_angle_tag(p.nominal_angle_deg);
        if (!maps.has_channel("tau_" + tag))
            fail("{}: no channel tau_{} for analyzer angle {:g}° listed in {}", maps_path, tag,
                 p.nominal_angle_deg, yaml_path);
        WireGridPosition pos{p.nominal_angle_deg, maps.channel("tau_" + tag),
                             maps.channel("B_" + tag), maps.channel("residual_" + tag)};
        // Maps written before tirpol recorded the fit's covariance have none; reductions then state
        // so.
        if (maps.has_channel("tau_var_" + tag) && maps.has_channel("B_var_" + tag) &&
            maps.has_channel("tau_B_cov_" + tag)) {
            pos.tau_var = maps.channel("tau_var_" + tag);
            pos.background_var = maps.channel("B_var_" + tag);
            pos.tau_background_cov = maps.channel("tau_B_cov_" + tag);
        }
        cal.wire_grid.positions.push_back(std::move(pos));
    }
    return cal;
}

}  // namespace tirpol::calibration
