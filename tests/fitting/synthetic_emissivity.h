#pragma once
// Simulated emissivity measurements for the fitting tests: the materials module's own integrator
// (materials::directional_emissivity, independent of the fit's fixed-node quadrature) evaluated at
// the true parameters, plus Gaussian noise of the stated uncertainty.

#include <cmath>
#include <random>
#include <vector>

#include "tirpol/core/geometry.h"
#include "tirpol/fitting/microfacet_fit.h"
#include "tirpol/materials/emissivity.h"
#include "tirpol/materials/microfacet.h"

namespace tirpol::fitting::test {

/// Flat black paint-like truth (n 1.55, k 0.12, σ 0.25, ρ_D 0.01; bias 1, no Beard–Maxwell
/// shadowing).
inline materials::ShellTargetParameters<double> paint_truth() {
    return {1.55, 0.12, 0.25, 1.0, deg_to_rad(90.0), deg_to_rad(1e6), 0.01, 0.0};
}

inline materials::MicrofacetBrdf brdf_of(const materials::ShellTargetParameters<double>& p) {
    materials::MicrofacetParameters mp;
    mp.index = materials::RefractiveIndexTable::constant({p.n, p.k});
    mp.sigma = p.sigma;
    mp.bias = p.bias;
    mp.tau_deg = rad_to_deg(p.tau_rad);
    mp.omega_deg = rad_to_deg(p.omega_rad);
    mp.rho_d = p.rho_d;
    mp.rho_v = p.rho_v;
    return materials::MicrofacetBrdf(mp);
}

/// Noise-free samples at the given angles (uncertainties attached but not applied).
inline EmissivityDataset clean_dataset(const materials::ShellTargetParameters<double>& truth,
                                       const std::vector<double>& angles_deg, double sigma_s0,
                                       double sigma_s1, double wavelength_um = 10.0) {
    const materials::MicrofacetBrdf brdf = brdf_of(truth);
    EmissivityDataset d{"simulated", wavelength_um, {}};
    for (double a : angles_deg) {
        const StokesVector e =
            materials::directional_emissivity(brdf, std::cos(deg_to_rad(a)), wavelength_um);
        d.samples.push_back({a, e(0), sigma_s0, e(1), sigma_s1, ""});
    }
    return d;
}

/// `clean` with independent Gaussian noise of each sample's sigma (fixed seed).
inline EmissivityDataset noisy(EmissivityDataset clean, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> normal;
    for (EmissivitySample& s : clean.samples) {
        s.eps_s0 += s.eps_s0_std * normal(rng);
        s.eps_s1 += s.eps_s1_std * normal(rng);
    }
    return clean;
}

/// 0°, 5°, …, 85° (18 angles), the paper's Fig. 1 range.
inline std::vector<double> fig1_angles() {
    std::vector<double> a;
    for (int i = 0; i <= 85; i += 5) a.push_back(i);
    return a;
}

}  // namespace tirpol::fitting::test
