#pragma once
/// \file emissivity_curve.h
/// Polarized emissivity versus emission angle for one material, as a table (CSV) and a plot like
/// the paper's Fig. 1 (ε_S0 and ε_S1 against angle), at one wavelength or averaged over a band.

#include <filesystem>
#include <string>
#include <vector>

#include "tirpol/core/radiometry.h"
#include "tirpol/core/stokes.h"
#include "tirpol/materials/pbrdf.h"

namespace tirpol::materials {

struct EmissivityRow {
    double angle_deg = 0.0;  ///< emission angle from the surface normal
    StokesVector e =
        StokesVector::Zero();  ///< ε as Stokes in the s/p frame (S1 < 0: in the plane of emission)
    double dolp = 0.0;         ///< degree of linear polarization of the emission
    double dhr = 0.0;          ///< directional-hemispherical reflectance 1 − ε_S0
};

/// Parses an angle list "0,45,60" or an inclusive range "START:STOP:STEP" (degrees, within [0,
/// 90]). Throws tirpol::Error naming the specification and what was expected.
std::vector<double> parse_angles_deg(const std::string& spec);

/// ε at one wavelength, integrated directly at every angle.
std::vector<EmissivityRow> emissivity_curve(const PolarizedBrdf& brdf,
                                            const std::vector<double>& angles_deg,
                                            double wavelength_um);

/// Planck(T)×RSR-weighted band average, from an EmissivityTable over the band (0.25 µm steps).
/// Throws if the band leaves the model's data range.
std::vector<EmissivityRow> emissivity_curve(const PolarizedBrdf& brdf,
                                            const std::vector<double>& angles_deg, const Band& band,
                                            double temperature_k);

/// CSV text with header angle_deg,e_s0,e_s1,e_s2,e_s3,dolp,dhr.
std::string emissivity_csv(const std::vector<EmissivityRow>& rows);

/// PNG plot of ε_S0 and ε_S1 against emission angle (paper Fig. 1 layout).
void write_emissivity_plot(const std::filesystem::path& path,
                           const std::vector<EmissivityRow>& rows, const std::string& title);

}  // namespace tirpol::materials
