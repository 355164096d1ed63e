#pragma once
/// \file surface_temperature.h
/// Surface temperature of a facet driven by weather: the slab solver (slab.h) with the surface
/// energy balance built from one weather record — solar (SPA sun position, direct + isotropic
/// diffuse + ground-reflected, shadow fraction), longwave (sky model or measured IR, sky view
/// factor, ground) and wind convection — spun up from the air temperature N hours before the
/// requested time.
///
/// One-dimensional multi-layer slab (the THERM model of DIRSIG, paper §2.2.2): heat conduction
/// through layers of given thickness, conductivity, density and specific heat, discretised by
/// cell-centred finite volumes (Patankar, Numerical Heat Transfer and Fluid Flow, 1980, ch. 4) and
/// stepped in time with the θ-method (θ = 1 backward Euler, θ = ½ Crank–Nicolson). The exposed
/// surface is a node without heat capacity whose energy balance — absorbed solar + absorbed
/// longwave − εσT⁴ − convection = conduction into the slab — is solved by Newton's method at each
/// step.

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "tirpol/core/geometry.h"
#include "tirpol/thermal/sky_longwave.h"
#include "tirpol/thermal/weather.h"

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

/// A material as the thermal model sees it.
struct ThermalMaterial {
    std::string name;
    SlabDefinition slab;
    double solar_absorptivity = 0.7;  ///< fraction of solar irradiance absorbed
    double thermal_emissivity = 0.9;  ///< broadband longwave emissivity (= absorptance)
};

/// Orientation of a surface element.
struct Facet {
    double tilt_deg = 0.0;       ///< 0 = facing up, 90 = vertical, 180 = facing down
    double azimuth_deg = 180.0;  ///< direction the normal points to, from north eastward
    /// Fraction of the hemisphere above the facet that is sky; NaN → (1 + cos tilt)/2
    /// (unobstructed).
    double sky_view_factor = kMissing;
};

/// Wind convection correlations.
enum class ConvectionModel {
    McAdams,  ///< h = 5.7 + 3.8 v (W/m²·K, v in m/s at the surface), McAdams, Heat Transmission,
              ///< 3rd ed. (1954), as given by Duffie & Beckman, Solar Engineering of Thermal
              ///< Processes §3.15
    Fixed,    ///< h = ThermalOptions::fixed_convection_w_m2_k
};

struct ThermalOptions {
    double spin_up_hours =
        24.0;  ///< start from the air temperature this long before the requested time
    double time_step_s = 300.0;
    /// Weight of the new time level in the θ-method step (slab.h): 1 backward Euler (robust), ½
    /// Crank–Nicolson.
    double implicit_weight = 1.0;
    ClearSkyModel sky_model = ClearSkyModel::BerdahlMartin1984;
    bool use_measured_sky_ir = true;  ///< use the record's horizontal IR when present
    ConvectionModel convection = ConvectionModel::McAdams;
    double fixed_convection_w_m2_k = 10.0;
    double ground_albedo = 0.2;  ///< when the record has none
    double delta_t_s = 69.0;     ///< ΔT for the SPA
    SlabGridOptions grid;
};

/// Shadow fraction (0 lit … 1 fully shadowed) of the facet's direct sun at an instant, given the
/// unit vector towards the sun (x east, y north, z up). The scene supplies it by ray tracing.
using ShadowFunction = std::function<double(double time_s, const Vec3& sun_direction)>;

/// Local apparent solar hour used by the Berdahl–Martin diurnal term: UTC hours + longitude/15.
double local_solar_hour(double time_s, double longitude_deg);

/// Broadband hemispherical sky emissivity of a record: E_IR/(σT_a⁴) from the measured horizontal IR
/// when present and `use_measured_sky_ir`, else `options.sky_model` with the Clark–Allen cloud
/// factor.
double broadband_sky_emissivity(const WeatherRecord& record, const Site& site,
                                const ThermalOptions& options);

/// The sky of one weather record: the renderer's sky and the solver's sky load (same numbers).
/// Broadband emissivity from the measured horizontal IR when present and `use_measured_sky_ir`,
/// else from `options.sky_model` with the Clark–Allen cloud factor; window emissivity from Idso
/// (1981).
SkyRadianceModel sky_from_weather(const WeatherRecord& record, const Site& site,
                                  const ThermalOptions& options);

/// Solar irradiance on a facet, W/m²: DNI cos(incidence) (1 − shadow) when the sun is above the
/// horizon and in front of the facet, + DHI (1 + cos tilt)/2 (isotropic sky) + GHI ρ_g (1 − cos
/// tilt)/2.
double facet_solar_irradiance_w_m2(const WeatherRecord& record, const Site& site,
                                   const Facet& facet, const ThermalOptions& options,
                                   const ShadowFunction& shadow = {});

/// Surface forcing for the slab solver at one instant.
SurfaceForcing facet_forcing(const WeatherRecord& record, const Site& site,
                             const ThermalMaterial& material, const Facet& facet,
                             const ThermalOptions& options, const ShadowFunction& shadow = {});

/// One sample of a simulated history.
struct TemperatureSample {
    double time_s = 0.0;
    double surface_temperature_k = 0.0;
    double air_temperature_k = 0.0;
    SurfaceFluxes fluxes;  ///< balance terms at the sample
};

/// Simulates the facet from `start_s` (uniform at the air temperature) to `end_s`, returning
/// samples every `sample_every_s` (multiple of the time step) from `record_from_s` on. Throws
/// tirpol::Error when the weather does not cover [start_s, end_s].
std::vector<TemperatureSample> simulate_facet(const WeatherSeries& weather,
                                              const ThermalMaterial& material, const Facet& facet,
                                              double start_s, double end_s, double record_from_s,
                                              double sample_every_s, const ThermalOptions& options,
                                              const ShadowFunction& shadow = {});

/// Surface temperature (K) of the facet at `time_s` after spin-up from `time_s − spin_up_hours`.
double predict_surface_temperature(const WeatherSeries& weather, const ThermalMaterial& material,
                                   const Facet& facet, double time_s, const ThermalOptions& options,
                                   const ShadowFunction& shadow = {});

/// One facet of a batch: its material (not owned), orientation and optional shadow function.
struct FacetRequest {
    const ThermalMaterial* material = nullptr;
    Facet facet;
    ShadowFunction shadow;
};

/// Surface temperatures (K) of many facets at `time_s`, spun up together: the weather, the sun and
/// the sky are evaluated once per step and shared by all facets (what a scene with many materials
/// and orientations needs). Same result as predict_surface_temperature for each facet.
std::vector<double> predict_surface_temperatures(const WeatherSeries& weather,
                                                 const std::vector<FacetRequest>& facets,
                                                 double time_s, const ThermalOptions& options);

}  // namespace tirpol::thermal
