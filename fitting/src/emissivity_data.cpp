#include <cmath>
#include <map>

#include "tirpol/core/atomic_file.h"
#include "tirpol/core/emissivity_csv.h"
#include "tirpol/core/error.h"
#include "tirpol/core/limits.h"
#include "tirpol/fitting/microfacet_fit.h"

namespace tirpol::fitting {

void validate_dataset(const EmissivityDataset& d) {
    if (!(std::isfinite(d.wavelength_um) && d.wavelength_um > 0.0))
        fail("{}: wavelength_um must be a positive number of micrometres, got {}", d.source,
             d.wavelength_um);
    if (d.samples.empty()) fail("{}: no emissivity samples", d.source);
    for (std::size_t i = 0; i < d.samples.size(); ++i) {
        const EmissivitySample& s = d.samples[i];
        const std::string which = fmt::format("{}: sample {}{}", d.source, i + 1,
                                              s.name.empty() ? "" : " (\"" + s.name + "\")");
        const std::pair<const char*, double> values[] = {{"angle_deg", s.angle_deg},
                                                         {"eps_s0", s.eps_s0},
                                                         {"eps_s0_std", s.eps_s0_std},
                                                         {"eps_s1", s.eps_s1},
                                                         {"eps_s1_std", s.eps_s1_std}};
        for (const auto& [field, value] : values)
            if (!std::isfinite(value))
                fail("{}: {} is {}; expected a finite number", which, field, value);
        if (s.angle_deg < 0.0 || s.angle_deg > 90.0)
            fail(
                "{}: view angle {}° is outside [0°, 90°] (angles are measured from the surface "
                "normal)",
                which, s.angle_deg);
        // Measured emissivities stray outside [0, 1] by noise only; far outside, the row is not an
        // emissivity.
        constexpr double tol = limits::kEmissivityTolerance;
        if (s.eps_s0 < -tol || s.eps_s0 > 1.0 + tol)
            fail(
                "{}: eps_s0 = {} is outside [{}, {}]; an emissivity lies in [0, 1] (a tolerance of "
                "{} is allowed for "
                "measurement noise)",
                which, s.eps_s0, -tol, 1.0 + tol, tol);
        if (std::abs(s.eps_s1) > 1.0 + tol)
            fail(
                "{}: eps_s1 = {} is outside [{}, {}]; a polarized emissivity lies in [-1, 1] (a "
                "tolerance of {} is "
                "allowed for measurement noise)",
                which, s.eps_s1, -1.0 - tol, 1.0 + tol, tol);
        if (!(s.eps_s0_std > 0.0) || !(s.eps_s1_std > 0.0))
            fail(
                "{}: uncertainties must be > 0 (got eps_s0_std = {}, eps_s1_std = {}); a zero "
                "uncertainty would "
                "give the sample infinite weight",
                which, s.eps_s0_std, s.eps_s1_std);
    }
}

std::vector<EmissivityDataset> load_emissivity_csv(const std::filesystem::path& path,
                                                   double default_wavelength_um) {
    if (!(std::isfinite(default_wavelength_um) && default_wavelength_um > 0.0))
        fail("default wavelength must be a positive number of micrometres, got {}",
             default_wavelength_um);
    const std::vector<EmissivityCsvRow> rows = parse_emissivity_csv(read_file(path), path.string());
    std::map<double, EmissivityDataset> by_wavelength;
    for (const EmissivityCsvRow& row : rows) {
        // An image-frame ε_S1 is the plane-of-emission one when that plane is vertical in the image
        // (the geometry docs/fitting.md asks for); other geometries are rotated before writing.
        const EmissivitySample s{row.view_angle_deg, row.eps_s0,     row.eps_s0_std,
                                 row.eps_s1,         row.eps_s1_std, row.name};
        const double wavelength = row.wavelength_um.value_or(default_wavelength_um);
        EmissivityDataset& d = by_wavelength[wavelength];
        d.wavelength_um = wavelength;
        d.source = row.wavelength_um ? fmt::format("{} ({} µm)", path.string(), wavelength)
                                     : path.string();
        // Validate row by row so that the message can name the line.
        validate_dataset({fmt::format("{}:{}", path.string(), row.line), wavelength, {s}});
        d.samples.push_back(s);
    }
    std::vector<EmissivityDataset> out;
    for (auto& [wavelength, d] : by_wavelength) out.push_back(std::move(d));
    return out;
}

std::string emissivity_csv(const std::vector<EmissivityDataset>& datasets) {
    std::vector<EmissivityCsvRow> rows;
    for (const EmissivityDataset& d : datasets)
        for (const EmissivitySample& s : d.samples) {
            EmissivityCsvRow r;
            r.name = s.name;
            r.view_angle_deg = s.angle_deg;
            r.frame = EmissivityFrame::PlaneOfEmission;
            r.eps_s0 = s.eps_s0;
            r.eps_s0_std = s.eps_s0_std;
            r.eps_s1 = s.eps_s1;
            r.eps_s1_std = s.eps_s1_std;
            r.wavelength_um = d.wavelength_um;
            rows.push_back(std::move(r));
        }
    return emissivity_csv_text(rows);
}

}  // namespace tirpol::fitting
