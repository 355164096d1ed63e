#include "tirpol/core/instrument_model.h"

#include <cmath>

#include "tirpol/core/geometry.h"

namespace tirpol {

AnalyzerAtAngle analyzer_at(const WireGridPolarizer& grid, double angle_deg) {
    const MuellerMatrix p = polarizer_with_extinction(deg_to_rad(angle_deg + grid.angle_offset_deg),
                                                      grid.transmission, grid.extinction_ratio);
    // The reflected term's polarization is referred to the nominal angle (the offset is a degree or
    // two and the term a small correction).
    const double reflected =
        grid.reflectance * grid.reflected_radiance *
        (1.0 + grid.reflection_polarization * std::cos(2.0 * deg_to_rad(angle_deg)));
    return {p.row(0), reflected + grid.emissivity * grid.emitted_radiance};
}

}  // namespace tirpol
