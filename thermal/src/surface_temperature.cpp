#include "tirpol/thermal/surface_temperature.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "tirpol/core/error.h"
#include "tirpol/thermal/solar_position.h"

namespace tirpol::thermal {

double local_solar_hour(double time_s, double longitude_deg) {
    const double h = std::fmod(time_s / 3600.0 + longitude_deg / 15.0, 24.0);
    return h < 0.0 ? h + 24.0 : h;
}

namespace {
SkyConditions sky_conditions(const WeatherRecord& r, const Site& site) {
    SkyConditions c;
    c.air_temperature_c = r.air_temperature_c;
    c.dew_point_c = std::min(r.dew_point_c, r.air_temperature_c);
    c.pressure_hpa = r.pressure_pa / 100.0;
    c.local_solar_hour = local_solar_hour(r.time_s, site.longitude_deg);
    // A file with measured IR but no sky cover: the window model and a fallback broadband model see
    // a clear sky.
    c.opaque_sky_cover_tenths =
        std::isnan(r.opaque_sky_cover_tenths) ? 0.0 : r.opaque_sky_cover_tenths;
    return c;
}
}  // namespace

double broadband_sky_emissivity(const WeatherRecord& r, const Site& site,
                                const ThermalOptions& options) {
    if (options.use_measured_sky_ir && !std::isnan(r.horizontal_ir_w_m2)) {
        const double ta_k = r.air_temperature_c + kZeroCelsiusK;
        return r.horizontal_ir_w_m2 / (kStefanBoltzmann * ta_k * ta_k * ta_k * ta_k);
    }
    return sky_emissivity(options.sky_model, sky_conditions(r, site));
}

SkyRadianceModel sky_from_weather(const WeatherRecord& r, const Site& site,
                                  const ThermalOptions& options) {
    return SkyRadianceModel(r.air_temperature_c + kZeroCelsiusK,
                            broadband_sky_emissivity(r, site, options),
                            window_sky_emissivity(sky_conditions(r, site)));
}

namespace {
SpaInput spa_input(double time_s, const Site& site, const WeatherRecord& r,
                   const ThermalOptions& options) {
    SpaInput in;
    in.unix_seconds = time_s;
    in.latitude_deg = site.latitude_deg;
    in.longitude_deg = site.longitude_deg;
    in.elevation_m = site.elevation_m;
    in.pressure_mbar = r.pressure_pa / 100.0;
    in.temperature_c = r.air_temperature_c;
    in.delta_t_s = options.delta_t_s;
    return in;
}
}  // namespace

namespace {

// What every facet shares at one instant: the weather, the sun (when there is direct sun) and the
// sky.
struct Environment {
    WeatherRecord record;
    std::optional<SolarPosition> sun;
    double sky_irradiance_w_m2 = 0.0;
    double air_k = 0.0;
};

Environment environment_at(const WeatherRecord& r, const Site& site,
                           const ThermalOptions& options) {
    Environment env;
    env.record = r;
    env.air_k = r.air_temperature_c + kZeroCelsiusK;
    if (r.direct_normal_w_m2 > 0.0) {
        const SolarPosition sun = solar_position(spa_input(r.time_s, site, r, options));
        if (sun.zenith_deg < 90.0) env.sun = sun;
    }
    env.sky_irradiance_w_m2 =
        broadband_sky_emissivity(r, site, options) * kStefanBoltzmann * std::pow(env.air_k, 4);
    return env;
}

double solar_on_facet(const Environment& env, const Facet& facet, const ThermalOptions& options,
                      const ShadowFunction& shadow) {
    const WeatherRecord& r = env.record;
    const double cos_tilt = std::cos(deg_to_rad(facet.tilt_deg));
    const double albedo = std::isnan(r.albedo) ? options.ground_albedo : r.albedo;
    double e = r.diffuse_horizontal_w_m2 * 0.5 * (1.0 + cos_tilt) +
               r.global_horizontal_w_m2 * albedo * 0.5 * (1.0 - cos_tilt);
    if (env.sun) {
        const double cos_i =
            std::cos(deg_to_rad(incidence_angle_deg(*env.sun, facet.tilt_deg, facet.azimuth_deg)));
        if (cos_i > 0.0) {
            const double lit =
                shadow ? 1.0 - std::clamp(shadow(r.time_s, sun_direction(*env.sun)), 0.0, 1.0)
                       : 1.0;
            e += r.direct_normal_w_m2 * cos_i * lit;
        }
    }
    return e;
}

SurfaceForcing forcing_from(const Environment& env, const ThermalMaterial& m, const Facet& facet,
                            const ThermalOptions& options, const ShadowFunction& shadow) {
    const double f_sky = std::isnan(facet.sky_view_factor)
                             ? 0.5 * (1.0 + std::cos(deg_to_rad(facet.tilt_deg)))
                             : std::clamp(facet.sky_view_factor, 0.0, 1.0);
    SurfaceForcing f;
    f.absorbed_shortwave_w_m2 = m.solar_absorptivity * solar_on_facet(env, facet, options, shadow);
    // The ground and nearby objects are taken as black at the air temperature.
    f.incident_longwave_w_m2 =
        f_sky * env.sky_irradiance_w_m2 + (1.0 - f_sky) * kStefanBoltzmann * std::pow(env.air_k, 4);
    f.emissivity = m.thermal_emissivity;
    f.air_temperature_k = env.air_k;
    f.convection_w_m2_k = options.convection == ConvectionModel::McAdams
                              ? 5.7 + 3.8 * env.record.wind_speed_m_s
                              : options.fixed_convection_w_m2_k;
    return f;
}

struct TimeGrid {
    long steps;
    double dt;
};

TimeGrid time_grid(const WeatherSeries& weather, double start_s, double end_s,
                   const ThermalOptions& options) {
    if (!(options.time_step_s > 0.0))
        fail("thermal: time step must be positive, got {} s", options.time_step_s);
    if (!(end_s >= start_s)) fail("thermal: end time before start time");
    // Fail before the loop, naming the span the weather file covers.
    weather.at(start_s);
    weather.at(end_s);
    const auto steps = static_cast<long>(std::ceil((end_s - start_s) / options.time_step_s - 1e-9));
    return {steps, steps > 0 ? (end_s - start_s) / static_cast<double>(steps) : 0.0};
}

}  // namespace

double facet_solar_irradiance_w_m2(const WeatherRecord& r, const Site& site, const Facet& facet,
                                   const ThermalOptions& options, const ShadowFunction& shadow) {
    return solar_on_facet(environment_at(r, site, options), facet, options, shadow);
}

SurfaceForcing facet_forcing(const WeatherRecord& r, const Site& site, const ThermalMaterial& m,
                             const Facet& facet, const ThermalOptions& options,
                             const ShadowFunction& shadow) {
    return forcing_from(environment_at(r, site, options), m, facet, options, shadow);
}

std::vector<TemperatureSample> simulate_facet(const WeatherSeries& weather,
                                              const ThermalMaterial& material, const Facet& facet,
                                              double start_s, double end_s, double record_from_s,
                                              double sample_every_s, const ThermalOptions& options,
                                              const ShadowFunction& shadow) {
    const TimeGrid grid = time_grid(weather, start_s, end_s, options);
    SlabModel slab(material.slab, options.grid);
    const WeatherRecord first = weather.at(start_s);
    slab.set_uniform_temperature(first.air_temperature_c + kZeroCelsiusK);
    const auto every = std::max<long>(1, std::lround(sample_every_s / std::max(grid.dt, 1e-9)));
    std::vector<TemperatureSample> out;
    auto record = [&](double t, const SurfaceForcing& f) {
        out.push_back({t, slab.surface_temperature_k(), f.air_temperature_k,
                       surface_fluxes(f, slab.surface_temperature_k())});
    };
    if (grid.steps == 0) {
        record(start_s, facet_forcing(first, weather.site(), material, facet, options, shadow));
        return out;
    }
    for (long i = 1; i <= grid.steps; ++i) {
        const double t = start_s + static_cast<double>(i) * grid.dt;
        const SurfaceForcing f =
            facet_forcing(weather.at(t), weather.site(), material, facet, options, shadow);
        slab.step(grid.dt, f, options.implicit_weight);
        const bool sample_due = (grid.steps - i) % every == 0;
        if (t >= record_from_s - 1e-6 && sample_due) record(t, f);
    }
    return out;
}

double predict_surface_temperature(const WeatherSeries& weather, const ThermalMaterial& material,
                                   const Facet& facet, double time_s, const ThermalOptions& options,
                                   const ShadowFunction& shadow) {
    return predict_surface_temperatures(weather, {{&material, facet, shadow}}, time_s, options)
        .front();
}

std::vector<double> predict_surface_temperatures(const WeatherSeries& weather,
                                                 const std::vector<FacetRequest>& facets,
                                                 double time_s, const ThermalOptions& options) {
    const double start = time_s - options.spin_up_hours * 3600.0;
    const TimeGrid grid = time_grid(weather, start, time_s, options);
    std::vector<SlabModel> slabs;
    slabs.reserve(facets.size());
    const double air0_k = weather.at(start).air_temperature_c + kZeroCelsiusK;
    for (const auto& req : facets) {
        slabs.emplace_back(req.material->slab, options.grid);
        slabs.back().set_uniform_temperature(air0_k);
    }
    for (long i = 1; i <= grid.steps; ++i) {
        const Environment env = environment_at(weather.at(start + static_cast<double>(i) * grid.dt),
                                               weather.site(), options);
        for (std::size_t k = 0; k < facets.size(); ++k)
            slabs[k].step(
                grid.dt,
                forcing_from(env, *facets[k].material, facets[k].facet, options, facets[k].shadow),
                options.implicit_weight);
    }
    std::vector<double> out;
    out.reserve(slabs.size());
    for (const auto& s : slabs) out.push_back(s.surface_temperature_k());
    return out;
}

}  // namespace tirpol::thermal
