#include <fmt/format.h>

#include <cmath>
#include <sstream>

#include "tirpol/core/error.h"
#include "tirpol/core/limits.h"
#include "tirpol/core/quicklook.h"
#include "tirpol/materials/emissivity.h"

namespace tirpol::materials {

namespace {
double angle_number(const std::string& text, const std::string& spec) {
    if (const auto v = tirpol::parse_number(text); v && std::isfinite(*v)) return *v;
    fail("angle specification \"{}\": \"{}\" is not a number (expected e.g. 0,45,60 or 0:85:5)",
         spec, text);
}

EmissivityRow make_row(double angle_deg, const StokesVector& e) {
    return {angle_deg, e, dolp(e), 1.0 - e(0)};
}
}  // namespace

std::vector<double> parse_angles_deg(const std::string& spec) {
    std::vector<double> angles;
    if (spec.find(':') != std::string::npos) {
        std::vector<std::string> parts;
        std::stringstream ss(spec);
        std::string p;
        while (std::getline(ss, p, ':')) parts.push_back(p);
        if (parts.size() != 3) fail("angle specification \"{}\": expected START:STOP:STEP", spec);
        const double start = angle_number(parts[0], spec), stop = angle_number(parts[1], spec),
                     step = angle_number(parts[2], spec);
        if (!(step > 0.0) || !(stop >= start) || !std::isfinite(start) || !std::isfinite(stop))
            fail("angle specification \"{}\": expected finite START ≤ STOP and STEP > 0", spec);
        constexpr double kMaxAngles = 100000;
        if ((stop - start) / step > kMaxAngles)
            fail("angle specification \"{}\": more than {} angles; use a larger STEP", spec,
                 kMaxAngles);
        const auto n = static_cast<long>(std::floor((stop - start) / step + 1e-9));
        for (long i = 0; i <= n; ++i) angles.push_back(start + static_cast<double>(i) * step);
    } else {
        std::stringstream ss(spec);
        std::string p;
        while (std::getline(ss, p, ',')) angles.push_back(angle_number(p, spec));
    }
    if (angles.empty()) fail("angle specification \"{}\": no angles", spec);
    for (double a : angles)
        if (!(a >= 0.0 && a <= 90.0))
            fail("angle specification \"{}\": {}° is outside [0, 90]", spec, a);
    return angles;
}

std::vector<EmissivityRow> emissivity_curve(const PolarizedBrdf& brdf,
                                            const std::vector<double>& angles_deg,
                                            double wavelength_um) {
    const auto [lo, hi] = brdf.valid_wavelength_range_um();
    if (!(wavelength_um >= lo && wavelength_um <= hi))
        fail("wavelength {} µm is outside the {} model's data range {}–{} µm", wavelength_um,
             brdf.model(), lo, hi);
    std::vector<EmissivityRow> rows;
    for (double a : angles_deg)
        rows.push_back(
            make_row(a, directional_emissivity(brdf, std::cos(deg_to_rad(a)), wavelength_um)));
    return rows;
}

std::vector<EmissivityRow> emissivity_curve(const PolarizedBrdf& brdf,
                                            const std::vector<double>& angles_deg, const Band& band,
                                            double temperature_k) {
    check_temperature_k(temperature_k, "emissivity curve: Planck weighting temperature");
    const EmissivityTable table(brdf, EmissivityTable::wavelengths_for_band(band));
    std::vector<EmissivityRow> rows;
    for (double a : angles_deg)
        rows.push_back(
            make_row(a, table.band_average(std::cos(deg_to_rad(a)), band, temperature_k)));
    return rows;
}

std::string emissivity_csv(const std::vector<EmissivityRow>& rows) {
    std::string out = "angle_deg,e_s0,e_s1,e_s2,e_s3,dolp,dhr\n";
    for (const auto& r : rows)
        out += fmt::format("{},{:.8f},{:.8f},{:.8f},{:.8f},{:.8f},{:.8f}\n", r.angle_deg, r.e(0),
                           r.e(1), r.e(2), r.e(3), r.dolp, r.dhr);
    return out;
}

void write_emissivity_plot(const std::filesystem::path& path,
                           const std::vector<EmissivityRow>& rows, const std::string& title) {
    PlotSeries s0{"emissivity S0", {}, {}, {31, 119, 180}, rows.size() <= 30};
    PlotSeries s1{"emissivity S1", {}, {}, {214, 39, 40}, rows.size() <= 30};
    double lowest = 0.0;
    for (const auto& r : rows) {
        s0.x.push_back(r.angle_deg);
        s0.y.push_back(r.e(0));
        s1.x.push_back(r.angle_deg);
        s1.y.push_back(r.e(1));
        lowest = std::min(lowest, r.e(1));
    }
    LinePlotOptions o;
    o.title = title;
    o.x_label = "emission angle (deg)";
    o.y_label = "polarized emissivity";
    o.x_min = 0.0;
    o.x_max = 90.0;
    o.y_min = std::min(-0.2, std::floor(lowest * 10.0) / 10.0);
    o.y_max = 1.0;
    o.legend_y_fraction = 0.5;  // the empty band between the ε_S0 and ε_S1 curves
    write_line_plot(path, {s0, s1}, o);
}

}  // namespace tirpol::materials
