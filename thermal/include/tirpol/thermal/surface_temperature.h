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
///
/// Weather that drives the surface temperatures and the sky: EnergyPlus EPW files and a simple CSV
/// for field logs (docs/thermal.md describes both), held as a time series of records with linear
/// interpolation in time.

#include <filesystem>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "tirpol/core/geometry.h"
#include "tirpol/thermal/sky_longwave.h"

namespace tirpol::thermal {

/// Where the weather (and the scene) is.
struct Site {
    std::string name;
    double latitude_deg = 0.0;   ///< north positive
    double longitude_deg = 0.0;  ///< east positive
    double utc_offset_h = 0.0;   ///< standard time zone, hours (UTC−7 → −7)
    double elevation_m = 0.0;
};

inline constexpr double kMissing = std::numeric_limits<double>::quiet_NaN();

/// One weather observation. State variables (temperature, humidity, pressure, wind, sky cover) are
/// instantaneous at `time_s`; radiation fields are averages over the interval that, for EPW files,
/// ends at `time_s` (WeatherSeries::at accounts for that).
struct WeatherRecord {
    double time_s = 0.0;  ///< UTC seconds since 1970 (civil_time.h)
    double air_temperature_c = 0.0;
    double dew_point_c = 0.0;
    double relative_humidity_pct = 0.0;
    double pressure_pa = 101325.0;
    double wind_speed_m_s = 0.0;
    double global_horizontal_w_m2 = 0.0;   ///< GHI
    double direct_normal_w_m2 = 0.0;       ///< DNI
    double diffuse_horizontal_w_m2 = 0.0;  ///< DHI
    double horizontal_ir_w_m2 =
        kMissing;  ///< measured downwelling longwave on a horizontal surface, or NaN
    double opaque_sky_cover_tenths = kMissing;  ///< 0–10, or NaN
    double albedo = kMissing;                   ///< ground solar reflectance, or NaN
};

/// A time-ordered series of records from one file.
class WeatherSeries {
public:
    /// `radiation_lag_s`: radiation fields of a record describe the interval ending at its time;
    /// they are interpolated as if observed `radiation_lag_s` earlier (half the interval for EPW, 0
    /// for instantaneous field logs). Throws tirpol::Error if fewer than two records or times not
    /// increasing.
    WeatherSeries(Site site, std::vector<WeatherRecord> records, std::string source,
                  double radiation_lag_s);

    const Site& site() const { return m_site; }
    const std::vector<WeatherRecord>& records() const { return m_records; }
    const std::string& source() const { return m_source; }
    double start_s() const { return m_records.front().time_s; }
    double end_s() const { return m_records.back().time_s; }

    /// The weather at instant `time_s`, linearly interpolated (radiation on its own, lagged, time
    /// axis). Throws tirpol::Error naming the file and its time span when `time_s` is outside it.
    WeatherRecord at(double time_s) const;

private:
    Site m_site;
    std::vector<WeatherRecord> m_records;
    std::string m_source;
    double m_radiation_lag_s;
};

/// Reads an EnergyPlus weather file (EnergyPlus Auxiliary Programs, "Weather Converter Program":
/// 8 header lines, LOCATION first; data lines of 35 fields; hour 1–24 is the hour ending at that
/// time, local standard time). Missing-value codes: dry bulb 99.9, wind 999 and the three solar
/// fields 9999 are errors; dew point 99.9 / relative humidity 999 are derived one from the other;
/// pressure 999999 → standard atmosphere at the site elevation; horizontal IR 9999, opaque sky
/// cover 99 and albedo 999 → missing (at least one of horizontal IR or opaque sky cover must be
/// present). `year`: put every record in this year (typical-year files mix years).
WeatherSeries load_epw(const std::filesystem::path& path, std::optional<int> year = std::nullopt);

/// Reads a field-log CSV (docs/thermal.md): columns `time` (ISO 8601; without an offset the site's
/// UTC offset applies), `air_temperature_c`, `relative_humidity_pct` or `dew_point_c`,
/// `wind_speed_m_s`, `global_horizontal_w_m2`; optional `direct_normal_w_m2` and
/// `diffuse_horizontal_w_m2` (both or neither; when absent GHI is split with Erbs et al. 1982),
/// `sky_ir_w_m2`, `pressure_pa`, `opaque_sky_cover_tenths`. Values are instantaneous. Errors name
/// the file, line and column: missing required columns or cells, times not increasing, gaps longer
/// than `max_gap_h`, out-of-range values.
WeatherSeries load_weather_csv(const std::filesystem::path& path, const Site& site,
                               double max_gap_h = 3.0);

/// Standard-atmosphere pressure (Pa) at `elevation_m` (ASHRAE Handbook—Fundamentals ch. 1, eq. 3).
double standard_pressure_pa(double elevation_m);

/// Diffuse fraction of global horizontal irradiance from the clearness index k_t (Erbs, Klein &
/// Duffie, Solar Energy 28 (1982) 293–302, hourly correlation).
double erbs_diffuse_fraction(double clearness_index);

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
