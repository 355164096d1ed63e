#pragma once
/// \file slab.h
/// One-dimensional multi-layer slab (the THERM model of DIRSIG, paper §2.2.2): heat conduction
/// through layers of given thickness, conductivity, density and specific heat, discretised by
/// cell-centred finite volumes (Patankar, Numerical Heat Transfer and Fluid Flow, 1980, ch. 4) and
/// stepped in time with the θ-method (θ = 1 backward Euler, θ = ½ Crank–Nicolson). The exposed
/// surface is a node without heat capacity whose energy balance — absorbed solar + absorbed
/// longwave − εσT⁴ − convection = conduction into the slab — is solved by Newton's method at each
/// step.

#include <optional>
#include <vector>

namespace tirpol::thermal {

/// A homogeneous layer; `cells` = 0 lets the grid options choose.
struct Layer {
    double thickness_m = 0.0;
    double conductivity_w_m_k = 0.0;
    double density_kg_m3 = 0.0;
    double specific_heat_j_kg_k = 0.0;
    int cells = 0;
};

/// What lies behind the last layer.
struct BackBoundary {
    enum class Kind {
        Adiabatic,         ///< no heat flow (an insulated back or a symmetry plane)
        FixedTemperature,  ///< back face held at `temperature_k`
        Ground,  ///< a soil layer of `ground_depth_m` (Incropera Table A.3 "soil": k 0.52 W/m·K,
                 ///< ρ 2050 kg/m³, c 1840 J/kg·K) whose bottom is held at `temperature_k`
    };
    Kind kind = Kind::Adiabatic;
    double temperature_k = 283.15;
    double ground_depth_m = 1.0;
};

struct SlabDefinition {
    std::vector<Layer> layers;  ///< front (exposed) layer first
    BackBoundary back;
};

struct SlabGridOptions {
    double max_cell_thickness_m =
        0.005;  ///< automatic cell count: ceil(thickness / this), at least 2
};

/// Boundary conditions on the exposed surface for one step (values at the end of the step).
struct SurfaceForcing {
    double absorbed_shortwave_w_m2 =
        0.0;  ///< solar absorptivity × solar irradiance on the facet (after shadowing)
    double incident_longwave_w_m2 =
        0.0;                  ///< longwave irradiance on the facet; absorbed fraction = emissivity
    double emissivity = 0.0;  ///< thermal emissivity (also the longwave absorptance, Kirchhoff)
    double air_temperature_k = 293.15;
    double convection_w_m2_k = 0.0;
    std::optional<double>
        prescribed_surface_temperature_k;  ///< Dirichlet condition instead of the balance
};

/// Surface terms of the balance at surface temperature `t_s` (W/m², positive into the surface).
struct SurfaceFluxes {
    double absorbed_shortwave = 0.0;
    double absorbed_longwave = 0.0;
    double emitted_longwave = 0.0;  ///< εσT_s⁴ (positive number, leaving)
    double convection = 0.0;        ///< h (T_a − T_s)
    double net() const {
        return absorbed_shortwave + absorbed_longwave - emitted_longwave + convection;
    }
};
SurfaceFluxes surface_fluxes(const SurfaceForcing& forcing, double surface_temperature_k);

/// What one step did.
struct StepReport {
    int newton_iterations = 0;
    double front_flux_w_m2 =
        0.0;  ///< θ-weighted conduction into the slab at the surface over the step
    double back_flux_w_m2 =
        0.0;  ///< θ-weighted conduction out of the slab at the back over the step
};

class SlabModel {
public:
    /// Throws tirpol::Error for an empty slab or a non-positive layer property (naming the layer).
    explicit SlabModel(const SlabDefinition& definition, const SlabGridOptions& grid = {});

    void set_uniform_temperature(double temperature_k);
    /// Advances by `dt_s` with the θ-method: `implicit_weight` ∈ [½, 1] of the new time level (1
    /// backward Euler, ½ Crank–Nicolson), the rest on the old.
    StepReport step(double dt_s, const SurfaceForcing& forcing, double implicit_weight = 1.0);

    double surface_temperature_k() const { return m_surface_k; }
    const std::vector<double>& cell_temperatures_k() const { return m_t; }
    /// Depth of each cell centre below the exposed surface, m.
    const std::vector<double>& cell_depths_m() const { return m_depth; }
    /// Σ ρ c Δx T over the cells, J/m² (relative to 0 K).
    double stored_energy_j_m2() const;
    /// Temperature at depth `z` by linear interpolation between the surface node and the cell
    /// centres.
    double temperature_at_depth_k(double depth_m) const;

private:
    std::vector<double> m_capacity;     // ρ c Δx per cell, J/(m²·K)
    std::vector<double> m_conductance;  // [0]: surface→cell 0 (2k/Δx); [i]: cell i−1→cell i
    std::vector<double> m_depth;
    double m_back_conductance = 0.0;  // last cell → back face (2k/Δx), fixed/ground only
    double m_back_temperature_k = 0.0;
    bool m_back_fixed = false;
    std::vector<double> m_t;
    double m_surface_k = 0.0;
    // Workspace for the tridiagonal solve (no allocation per step).
    std::vector<double> m_a, m_b, m_c, m_r, m_x, m_bw, m_rw;
};

}  // namespace tirpol::thermal
