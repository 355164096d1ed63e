// Uses the installed tirpol like any downstream program: Planck band radiance against the
// Stefan–Boltzmann law, DoLP of a Stokes vector from four polarizer readings, and a material from
// the installed library. Exit status 0 when every check holds; each failure is printed.

#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>

#include "tirpol/core/radiometry.h"
#include "tirpol/core/stokes.h"
#include "tirpol/materials/material.h"

namespace {

int failures = 0;

void check_near(const char* what, double got, double expected, double rel_tol) {
    const bool ok = std::abs(got - expected) <= rel_tol * std::abs(expected);
    std::printf("%s %s: %.10g (expected %.10g, rel tol %g)\n", ok ? "ok  " : "FAIL", what, got,
                expected, rel_tol);
    if (!ok) ++failures;
}

}  // namespace

int main() {
    // ∫ L(λ, T) dλ = σT⁴/π, σ = 5.670374419e-8 W m⁻² K⁻⁴ (CODATA 2018). The 0.2–1000 µm band (the
    // longest wavelength a Band accepts) misses the tail beyond Λ = 1000 µm, added from the series
    // of Planck's law in x = hc/(λkT) < 0.05 there: ∫_Λ^∞ L dλ = 2ckT/(3Λ³) − hc²/(4Λ⁴) +
    // h²c³/(30kTΛ⁵) − …
    constexpr double kSigmaCodata2018 = 5.670374419e-8;
    constexpr double kPi = 3.14159265358979323846;
    constexpr double c = 299792458.0, k = 1.380649e-23, h = 6.62607015e-34;
    const tirpol::Band all(0.2, 1000.0, std::nullopt, 1.0);
    const double t_k = 300.0;
    const double l = 1000e-6;
    const double tail = 2.0 * c * k * t_k / (3.0 * l * l * l) - h * c * c / (4.0 * l * l * l * l) +
                        h * h * c * c * c / (30.0 * k * t_k * l * l * l * l * l);
    check_near("band radiance 0.2-1000 um at 300 K plus the tail, W/(m2 sr)",
               all.radiance(t_k) + tail, kSigmaCodata2018 * std::pow(t_k, 4) / kPi, 2e-8);

    // Polarizer readings at 0°, 45°, 90°, 135° of light 60 % linearly polarized along 0°:
    // S0 = I0 + I90, S1 = I0 − I90, S2 = I45 − I135, so DoLP = 0.6.
    const double i0 = 0.8, i45 = 0.5, i90 = 0.2, i135 = 0.5;
    const tirpol::StokesVector s{i0 + i90, i0 - i90, i45 - i135, 0.0};
    check_near("DoLP from four polarizer readings", tirpol::dolp(s), 0.6, 1e-12);

    try {
        const auto file =
            std::filesystem::path(TIRPOL_INSTALLED_CONFIG_DIR) / "materials" / "snow.yaml";
        const auto material = tirpol::materials::load_material(file);
        std::printf("ok   installed material %s: %s\n", file.c_str(), material.name.c_str());
    } catch (const std::exception& e) {
        std::printf("FAIL installed material library: %s\n", e.what());
        ++failures;
    }
    return failures == 0 ? 0 : 1;
}
