#include "tirpol/simulation/thermal/surface_temperature.h"

#include <algorithm>
#include <cmath>

#include "tirpol/core/error.h"
#include "tirpol/simulation/thermal/solar_position.h"

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
    // A file with measured IR but no sky cover: the window model and a fallback broadband model see a clear sky.
    c.opaque_sky_cover_tenths = std::isnan(r.opaque_sky_cover_tenths) ? 0.0 : r.opaque_sky_cover_tenths;
    return c;
}
}  // namespace

double broadband_sky_emissivity(const WeatherRecord& r, const Site& site, const ThermalOptions& options) {
    if (options.use_measured_sky_ir && !std::isnan(r.horizontal_ir_w_m2)) {
        const double ta_k = r.air_temperature_c + kZeroCelsiusK;
        return r.horizontal_ir_w_m2 / (kStefanBoltzmann * ta_k * ta_k * ta_k * ta_k);
    }
    return sky_emissivity(options.sky_model, sky_conditions(r, site));
}

SkyRadianceModel sky_from_weather(const WeatherRecord& r, const Site& site, const ThermalOptions& options) {
    return SkyRadianceModel(r.air_temperature_c + kZeroCelsiusK, broadband_sky_emissivity(r, site, options),
                            window_sky_emissivity(sky_conditions(r, site)));
}

namespace {
SpaInput spa_input(double time_s, const Site& site, const WeatherRecord& r, const ThermalOptions& options) {
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

double facet_solar_irradiance_w_m2(const WeatherRecord& r, const Site& site, const Facet& facet,
                                   const ThermalOptions& options, const ShadowFunction& shadow) {
    const double cos_tilt = std::cos(deg_to_rad(facet.tilt_deg));
    const double albedo = std::isnan(r.albedo) ? options.ground_albedo : r.albedo;
    double e = r.diffuse_horizontal_w_m2 * 0.5 * (1.0 + cos_tilt) + r.global_horizontal_w_m2 * albedo * 0.5 * (1.0 - cos_tilt);
    if (r.direct_normal_w_m2 > 0.0) {
        const SolarPosition sun = solar_position(spa_input(r.time_s, site, r, options));
        if (sun.zenith_deg < 90.0) {
            const double cos_i = std::cos(deg_to_rad(incidence_angle_deg(sun, facet.tilt_deg, facet.azimuth_deg)));
            if (cos_i > 0.0) {
                const double lit = shadow ? 1.0 - std::clamp(shadow(r.time_s, sun_direction(sun)), 0.0, 1.0) : 1.0;
                e += r.direct_normal_w_m2 * cos_i * lit;
            }
        }
    }
    return e;
}

SurfaceForcing facet_forcing(const WeatherRecord& r, const Site& site, const ThermalMaterial& m, const Facet& facet,
                             const ThermalOptions& options, const ShadowFunction& shadow) {
    const double ta_k = r.air_temperature_c + kZeroCelsiusK;
    const double sky_irradiance = broadband_sky_emissivity(r, site, options) * kStefanBoltzmann * std::pow(ta_k, 4);
    const double f_sky = std::isnan(facet.sky_view_factor) ? 0.5 * (1.0 + std::cos(deg_to_rad(facet.tilt_deg)))
                                                           : std::clamp(facet.sky_view_factor, 0.0, 1.0);
    SurfaceForcing f;
    f.absorbed_shortwave_w_m2 = m.solar_absorptivity * facet_solar_irradiance_w_m2(r, site, facet, options, shadow);
    // The ground and nearby objects are taken as black at the air temperature.
    f.incident_longwave_w_m2 = f_sky * sky_irradiance + (1.0 - f_sky) * kStefanBoltzmann * std::pow(ta_k, 4);
    f.emissivity = m.thermal_emissivity;
    f.air_temperature_k = ta_k;
    f.convection_w_m2_k = options.convection == ConvectionModel::McAdams ? 5.7 + 3.8 * r.wind_speed_m_s
                                                                         : options.fixed_convection_w_m2_k;
    return f;
}

std::vector<TemperatureSample> simulate_facet(const WeatherSeries& weather, const ThermalMaterial& material,
                                              const Facet& facet, double start_s, double end_s, double record_from_s,
                                              double sample_every_s, const ThermalOptions& options,
                                              const ShadowFunction& shadow) {
    if (!(options.time_step_s > 0.0)) fail("thermal: time step must be positive, got {} s", options.time_step_s);
    if (!(end_s >= start_s)) fail("thermal: end time before start time");
    // Fail before the loop, naming the span the weather file covers.
    weather.at(start_s);
    weather.at(end_s);
    SlabModel slab(material.slab, options.grid);
    const WeatherRecord first = weather.at(start_s);
    slab.set_uniform_temperature(first.air_temperature_c + kZeroCelsiusK);
    const auto steps = static_cast<long>(std::ceil((end_s - start_s) / options.time_step_s - 1e-9));
    const double dt = steps > 0 ? (end_s - start_s) / static_cast<double>(steps) : 0.0;
    const auto every = std::max<long>(1, std::lround(sample_every_s / std::max(dt, 1e-9)));
    std::vector<TemperatureSample> out;
    auto record = [&](double t, const SurfaceForcing& f) {
        out.push_back({t, slab.surface_temperature_k(), f.air_temperature_k, surface_fluxes(f, slab.surface_temperature_k())});
    };
    if (steps == 0) {
        record(start_s, facet_forcing(first, weather.site(), material, facet, options, shadow));
        return out;
    }
    for (long i = 1; i <= steps; ++i) {
        const double t = start_s + static_cast<double>(i) * dt;
        const SurfaceForcing f = facet_forcing(weather.at(t), weather.site(), material, facet, options, shadow);
        slab.step(dt, f, options.theta);
        const bool sample_due = (steps - i) % every == 0;
        if (t >= record_from_s - 1e-6 && sample_due) record(t, f);
    }
    return out;
}

double predict_surface_temperature(const WeatherSeries& weather, const ThermalMaterial& material, const Facet& facet,
                                   double time_s, const ThermalOptions& options, const ShadowFunction& shadow) {
    const double start = time_s - options.spin_up_hours * 3600.0;
    const auto samples = simulate_facet(weather, material, facet, start, time_s, time_s, options.time_step_s, options, shadow);
    return samples.back().surface_temperature_k;
}

}  // namespace tirpol::thermal
