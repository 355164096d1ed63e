// The slab solver against analytic solutions of the heat equation.
// Sources: H. S. Carslaw & J. C. Jaeger, Conduction of Heat in Solids, 2nd ed. (1959) — §2.5 (step
// in surface temperature, eq. 2.5(2)), §2.9 (constant surface flux, eq. 2.9(7)), §2.6 (periodic
// surface temperature, eq. 2.6(8)); F. P. Incropera et al., Fundamentals of Heat and Mass Transfer,
// 6th ed. (2007) — eqs. 5.57, 5.58 (same solutions), §3.1 (plane wall with convection, thermal
// resistances).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "tirpol/core/geometry.h"
#include "tirpol/thermal/sky_longwave.h"
#include "tirpol/thermal/surface_temperature.h"

namespace tirpol::thermal {
namespace {

// A concrete-like material: α = k/(ρc) = 1.4/(2300·880) ≈ 6.9e-7 m²/s.
constexpr double kK = 1.4, kRho = 2300.0, kC = 880.0;
constexpr double kAlpha = kK / (kRho * kC);

SlabDefinition deep_slab(double thickness_m, int cells) {
    SlabDefinition def;
    def.layers.push_back({thickness_m, kK, kRho, kC, cells});
    return def;
}

TEST(ThermalSlab, StepInSurfaceTemperatureFollowsErfSolution) {
    // Carslaw & Jaeger §2.5: T(x,t) = T_s + (T_i − T_s) erf(x / 2√(αt)). 1 m deep ≈ 7 diffusion
    // lengths at 6 h.
    SlabModel slab(deep_slab(1.0, 500));
    const double ti = 280.0, ts = 300.0;
    slab.set_uniform_temperature(ti);
    SurfaceForcing f;
    f.prescribed_surface_temperature_k = ts;
    const double dt = 30.0, t_end = 6 * 3600.0;
    for (double t = 0; t < t_end - 1e-9; t += dt) slab.step(dt, f, 0.5);
    for (double x : {0.01, 0.03, 0.06, 0.1, 0.2}) {
        const double exact = ts + (ti - ts) * std::erf(x / (2.0 * std::sqrt(kAlpha * t_end)));
        EXPECT_NEAR(slab.temperature_at_depth_k(x), exact, 0.01) << "depth " << x << " m";
    }
}

TEST(ThermalSlab, ConstantSurfaceFluxFollowsCarslawJaeger) {
    // Carslaw & Jaeger §2.9 / Incropera eq. 5.58: surface temperature rise 2q√(αt/π)/k, and
    // T − T_i = (2q/k)√(αt/π) exp(−x²/4αt) − (q x/k) erfc(x/2√(αt)) inside.
    SlabModel slab(deep_slab(1.0, 500));
    const double ti = 290.0, q = 400.0;
    slab.set_uniform_temperature(ti);
    SurfaceForcing f;
    f.absorbed_shortwave_w_m2 = q;  // no emission, no convection: pure flux
    const double dt = 30.0, t_end = 4 * 3600.0;
    for (double t = 0; t < t_end - 1e-9; t += dt) slab.step(dt, f, 0.5);
    const double at = kAlpha * t_end;
    auto exact = [&](double x) {
        return ti + 2.0 * q / kK * std::sqrt(at / kPi) * std::exp(-x * x / (4.0 * at)) -
               q * x / kK * std::erfc(x / (2.0 * std::sqrt(at)));
    };
    EXPECT_NEAR(slab.surface_temperature_k(), exact(0.0), 0.02);
    for (double x : {0.02, 0.05, 0.1})
        EXPECT_NEAR(slab.temperature_at_depth_k(x), exact(x), 0.02) << x;
}

// Runs a periodic surface temperature T_m + A cos(ωt) for `periods` days and returns the amplitude
// and phase (of cos(ωt − φ)) of the temperature at depth x over the last period.
struct Harmonic {
    double amplitude, phase_rad;
};
Harmonic periodic_response(double x, double dt, double theta, double cell_m, int periods = 6) {
    const double period = 86400.0, omega = 2.0 * kPi / period, tm = 290.0, a = 10.0;
    SlabModel slab(deep_slab(1.5, static_cast<int>(std::lround(1.5 / cell_m))));
    slab.set_uniform_temperature(tm);
    SurfaceForcing f;
    const int steps = static_cast<int>(std::lround(period / dt));
    double c = 0.0, s = 0.0;
    for (int p = 0; p < periods; ++p) {
        for (int i = 1; i <= steps; ++i) {
            const double t = (p * steps + i) * dt;
            f.prescribed_surface_temperature_k = tm + a * std::cos(omega * t);
            slab.step(dt, f, theta);
            if (p == periods - 1) {
                const double dev = slab.temperature_at_depth_k(x) - tm;
                c += dev * std::cos(omega * t);
                s += dev * std::sin(omega * t);
            }
        }
    }
    c *= 2.0 / steps;
    s *= 2.0 / steps;
    return {std::hypot(c, s) / a, std::atan2(s, c)};
}

TEST(ThermalSlab, PeriodicSurfaceTemperatureHasDampingDepthAndPhaseLag) {
    // Carslaw & Jaeger §2.6: T = T_m + A e^(−x/d) cos(ωt − x/d), damping depth d = √(2α/ω).
    const double d = std::sqrt(2.0 * kAlpha / (2.0 * kPi / 86400.0));
    for (double x : {0.05, 0.1, 0.2}) {
        const Harmonic h = periodic_response(x, 300.0, 0.5, 0.005);
        EXPECT_NEAR(h.amplitude, std::exp(-x / d), 2e-3) << "depth " << x;
        EXPECT_NEAR(h.phase_rad, x / d, 5e-3) << "depth " << x;
    }
}

TEST(ThermalSlab, TimeSteppingConvergesWithExpectedOrder) {
    // Error of the amplitude ratio at 0.1 m against the analytic value, halving the step: backward
    // Euler is first order (ratio ≈ 2), Crank–Nicolson second order (ratio ≈ 4). Fine grid so the
    // spatial error is negligible.
    const double d = std::sqrt(2.0 * kAlpha / (2.0 * kPi / 86400.0));
    const double exact = std::exp(-0.1 / d);
    auto err = [&](double dt, double theta) {
        return std::abs(periodic_response(0.1, dt, theta, 0.0025, 4).amplitude - exact);
    };
    const double be_ratio = err(3600.0, 1.0) / err(1800.0, 1.0);
    const double cn_ratio = err(3600.0, 0.5) / err(1800.0, 0.5);
    std::printf("time-step error ratios on halving dt: backward Euler %.3f, Crank-Nicolson %.3f\n",
                be_ratio, cn_ratio);
    EXPECT_NEAR(be_ratio, 2.0, 0.25);
    EXPECT_NEAR(cn_ratio, 4.0, 0.6);
}

TEST(ThermalSlab, GridConvergesWithSecondOrder) {
    // Cell-centred finite volumes with a surface node: second order in space (ratio ≈ 4 on
    // halving).
    const double d = std::sqrt(2.0 * kAlpha / (2.0 * kPi / 86400.0));
    const double exact = std::exp(-0.1 / d);
    auto err = [&](double cell) {
        return std::abs(periodic_response(0.1, 60.0, 0.5, cell, 4).amplitude - exact);
    };
    const double ratio = err(0.02) / err(0.01);
    std::printf("grid error ratio on halving the cell size: %.3f\n", ratio);
    EXPECT_NEAR(ratio, 4.0, 0.8);
}

TEST(ThermalSlab, SteadyMultiLayerWallWithSurfaceFilmMatchesResistanceNetwork) {
    // Incropera §3.1: q = (T_a − T_b) / (1/h + Σ L_i/k_i); temperatures drop linearly within each
    // layer.
    SlabDefinition def;
    def.layers = {
        {0.01, 0.16, 1000, 1500, 4}, {0.10, 0.04, 30, 1400, 10}, {0.15, 1.4, 2300, 880, 10}};
    def.back = {BackBoundary::Kind::FixedTemperature, 293.15, 1.0};
    SlabModel slab(def);
    slab.set_uniform_temperature(293.15);
    SurfaceForcing f;
    f.air_temperature_k = 263.15;
    f.convection_w_m2_k = 25.0;
    for (int i = 0; i < 400; ++i) slab.step(3600.0 * 24, f, 1.0);  // backward Euler to steady state
    const double r_total = 1.0 / 25.0 + 0.01 / 0.16 + 0.10 / 0.04 + 0.15 / 1.4;
    const double q = (293.15 - 263.15) / r_total;  // from the back towards the air
    EXPECT_NEAR(slab.surface_temperature_k(), 263.15 + q / 25.0, 1e-6);
    // Every cell centre lies on the piecewise-linear exact profile (finite volumes with harmonic
    // face conductances are exact for steady 1D conduction).
    auto exact = [&](double z) {
        double t = 263.15 + q / 25.0, top = 0.0;
        for (const Layer& l : def.layers) {
            const double within = std::min(std::max(z - top, 0.0), l.thickness_m);
            t += q * within / l.conductivity_w_m_k;
            top += l.thickness_m;
        }
        return t;
    };
    ASSERT_EQ(slab.cell_depths_m().size(), 24u);
    for (std::size_t j = 0; j < slab.cell_depths_m().size(); ++j)
        EXPECT_NEAR(slab.cell_temperatures_k()[j], exact(slab.cell_depths_m()[j]), 1e-6)
            << "cell " << j;
}

TEST(ThermalSlab, InsulatedPlateReachesRadiativeConvectiveBalance) {
    // Steady balance of a sunlit plate with an insulated back: α_s G + ε L↓ = εσT⁴ + h (T − T_a).
    // Reference root by bisection, independent of the solver's Newton iteration.
    SlabDefinition def;
    def.layers = {{0.002, 200.0, 2700.0, 900.0, 2}};
    SlabModel slab(def);
    slab.set_uniform_temperature(290.0);
    SurfaceForcing f;
    f.absorbed_shortwave_w_m2 = 0.6 * 800.0;
    f.incident_longwave_w_m2 = 300.0;
    f.emissivity = 0.9;
    f.air_temperature_k = 293.15;
    f.convection_w_m2_k = 10.0;
    for (int i = 0; i < 200; ++i) slab.step(600.0, f, 1.0);
    double lo = 250.0, hi = 450.0;
    for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        (surface_fluxes(f, mid).net() > 0.0 ? lo : hi) = mid;
    }
    EXPECT_NEAR(slab.surface_temperature_k(), lo, 1e-6);
    EXPECT_NEAR(surface_fluxes(f, slab.surface_temperature_k()).net(), 0.0, 1e-4);
}

TEST(ThermalSlab, TimeSteppingConservesEnergy) {
    // Change of stored energy = ∫(front flux − back flux) dt, to round-off, for both θ and any
    // forcing.
    for (double theta : {1.0, 0.5}) {
        SlabDefinition def;
        def.layers = {{0.02, 0.5, 1200, 1500, 0}, {0.1, 1.4, 2300, 880, 0}};
        def.back = {BackBoundary::Kind::Ground, 285.0, 0.5};
        SlabModel slab(def);
        slab.set_uniform_temperature(288.0);
        const double e0 = slab.stored_energy_j_m2();
        double in = 0.0;
        SurfaceForcing f;
        f.emissivity = 0.95;
        f.convection_w_m2_k = 12.0;
        for (int i = 0; i < 288; ++i) {
            f.absorbed_shortwave_w_m2 = std::max(0.0, 700.0 * std::sin(2.0 * kPi * i / 288.0));
            f.incident_longwave_w_m2 = 300.0 + 20.0 * std::cos(0.1 * i);
            f.air_temperature_k = 288.0 + 5.0 * std::sin(2.0 * kPi * (i - 40) / 288.0);
            const StepReport r = slab.step(300.0, f, theta);
            in += 300.0 * (r.front_flux_w_m2 - r.back_flux_w_m2);
            EXPECT_LT(r.newton_iterations, 10);
        }
        EXPECT_NEAR(slab.stored_energy_j_m2() - e0, in, 1e-9 * std::abs(e0));
        EXPECT_GT(std::abs(in), 1e4);  // the test moved a meaningful amount of energy
    }
}

}  // namespace
}  // namespace tirpol::thermal
