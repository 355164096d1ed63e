#include "tirpol/calibration/synthetic_session.h"

#include <fmt/format.h>

#include <cmath>
#include <random>

#include "tirpol/core/geometry.h"
#include "tirpol/core/instrument_model.h"
#include "tirpol/core/session.h"

namespace tirpol::calibration {

namespace {
struct PixelTruth {
    double gain, offset, noise;
};

std::vector<PixelTruth> pixel_truth(const SyntheticCamera& cam) {
    std::mt19937 rng(cam.seed);
    std::normal_distribution<double> unit(0.0, 1.0);
    std::vector<PixelTruth> px;
    for (int i = 0; i < cam.width * cam.height; ++i)
        px.push_back({cam.gain_mean * (1.0 + cam.gain_rel_std * unit(rng)),
                      cam.offset_mean + cam.offset_std * unit(rng), cam.noise_counts});
    auto at = [&](int x, int y) -> PixelTruth& {
        return px[static_cast<std::size_t>(y * cam.width + x)];
    };
    at(cam.dead_x, cam.dead_y).gain *= 0.02;
    at(cam.hot_x, cam.hot_y).offset += 3000.0;
    at(cam.noisy_x, cam.noisy_y).noise *= 12.0;
    return px;
}

Image uniform_scene(int w, int h, double s0) {
    Image s(w, h);
    s.add_channel("S0", static_cast<float>(s0));
    s.add_channel("S1");
    s.add_channel("S2");
    return s;
}

/// Core's forward model of the synthetic camera's wire grid over `band`.
WireGridPolarizer synthetic_wire_grid(const SyntheticCamera& cam, const Band& band) {
    WireGridPolarizer grid;
    grid.transmission = cam.t_max;
    grid.extinction_ratio = cam.extinction_ratio;
    grid.angle_offset_deg = cam.angle_offset_deg;
    grid.reflectance = cam.grid_reflectance;
    grid.reflected_radiance = band.radiance(cam.sky_temperature_k);
    // The grid reflects toward the camera the polarization it does not transmit: the sky term is
    // partly polarized across the wires, so it changes with the angle.
    grid.reflection_polarization = cam.sky_polarization;
    grid.emissivity = cam.grid_emissivity;
    grid.emitted_radiance = band.radiance(cam.grid_temperature_k);
    return grid;
}

}  // namespace

Image synthetic_record_frame(const SyntheticCamera& cam, const Image& scene, const Band& band,
                             double angle_deg, bool through_polarizer, bool field, unsigned seed) {
    const auto px = pixel_truth(cam);
    const AnalyzerAtAngle analyzer = analyzer_at(synthetic_wire_grid(cam, band), angle_deg);
    std::mt19937 rng(seed);
    std::normal_distribution<double> unit(0.0, 1.0);
    Image out(cam.width, cam.height);
    auto& counts = out.add_channel("counts");
    auto& counts_std = out.add_channel("counts_std");
    const auto& s0 = scene.channel("S0");
    const auto& s1 = scene.channel("S1");
    const auto& s2 = scene.channel("S2");
    const double saturation = std::ldexp(1.0, cam.bits_per_pixel) - 1.0;
    for (int y = 0; y < cam.height; ++y)
        for (int x = 0; x < cam.width; ++x) {
            const std::size_t i = static_cast<std::size_t>(y * cam.width + x);
            double l = s0[i];
            if (through_polarizer) {
                const double r2 = std::pow((x - cam.width / 2.0) / cam.width, 2) +
                                  std::pow((y - cam.height / 2.0) / cam.height, 2);
                const double ghost =
                    cam.ghost_radiance * std::exp(-(std::pow(x - 0.3 * cam.width, 2) +
                                                    std::pow(y - 0.4 * cam.height, 2)) /
                                                  (0.02 * cam.width * cam.width));
                l = analyzer.radiance(StokesVector(s0[i], s1[i], s2[i], 0.0),
                                      1.0 - cam.vignetting * r2) +
                    ghost;
            }
            const auto& p = px[i];
            const double offset = p.offset + (field ? cam.field_offset_drift : 0.0);
            const double mean = detector_counts(
                l, p.gain, offset, p.noise / std::sqrt(static_cast<double>(cam.frames)), unit(rng));
            counts[i] = static_cast<float>(std::min(mean, saturation));
            counts_std[i] = static_cast<float>(p.noise);
        }
    return out;
}

void write_synthetic_sessions(const std::filesystem::path& root, const SyntheticCamera& cam,
                              const Image& scene, const Band& band) {
    SessionManifest base;
    base.created_utc = utc_now_iso8601();
    base.camera = {"sim://synthetic", "tirpol",   "synthetic-uncooled", "0001", "Mono14",
                   cam.width,         cam.height, cam.bits_per_pixel,   30.0,   {}};
    base.stage = {"sim://stage", "tirpol", "synthetic-stage", "0001", "1.0", 1000.0};
    unsigned seed = cam.seed * 1000u;
    std::int64_t t_ns = 1795359560000000000;
    auto record = [&](RecordKind kind, const std::string& stem, double angle, int repeat,
                      std::optional<double> t_k) {
        SessionRecord r;
        r.kind = kind;
        r.file = session_frame_file(stem);
        r.angle_deg_requested = angle;
        r.angle_deg_measured = angle;
        r.repeat = repeat;
        r.blackbody_temperature_k = t_k;
        r.frames = cam.frames;
        r.first_timestamp_ns = t_ns;
        t_ns += 500000000;
        r.last_timestamp_ns = t_ns;
        return r;
    };

    {  // Laboratory: blackbody without the polarizer.
        SessionManifest m = base;
        m.metadata = {{"site", "laboratory"}, {"polarizer_in_beam", false}};
        auto w = SessionWriter::create(root / "lab", m);
        for (double t : {283.15, 298.15, 313.15, 328.15})
            w.add_record(
                record(RecordKind::Blackbody, fmt::format("bb_{:.2f}K", t), 0.0, 0, t),
                synthetic_record_frame(cam, uniform_scene(cam.width, cam.height, band.radiance(t)),
                                       band, 0.0, false, false, ++seed));
        w.mark_complete();
    }
    {  // Field, same night: blackbody through the polarizer, and the known polarized source.
        SessionManifest m = base;
        nlohmann::json known = nlohmann::json::array();
        int repeat = 1;
        for (double t : {288.15, 318.15})
            for (double ref : {0.0, 45.0, 90.0, 135.0})
                known.push_back({{"repeat", repeat++},
                                 {"blackbody_temperature_k", t},
                                 {"reference_polarizer_deg", ref}});
        m.metadata = {{"site", "field"}, {"polarizer_in_beam", true}, {"known_source", known}};
        auto w = SessionWriter::create(root / "polcal", m);
        for (double a : cam.angles_deg)
            for (double t : {278.15, 308.15})
                w.add_record(record(RecordKind::Blackbody,
                                    fmt::format("bb_{:.2f}K_{:.1f}deg", t, a), a, 0, t),
                             synthetic_record_frame(
                                 cam, uniform_scene(cam.width, cam.height, band.radiance(t)), band,
                                 a, true, true, ++seed));
        for (const auto& k : known) {
            const double l = band.radiance(k["blackbody_temperature_k"].get<double>());
            const double two_theta = 2.0 * deg_to_rad(k["reference_polarizer_deg"].get<double>());
            Image source(cam.width, cam.height);
            source.add_channel("S0", static_cast<float>(0.5 * l));
            source.add_channel("S1", static_cast<float>(0.5 * l * std::cos(two_theta)));
            source.add_channel("S2", static_cast<float>(0.5 * l * std::sin(two_theta)));
            const int rep = k["repeat"].get<int>();
            for (double a : cam.angles_deg)
                w.add_record(
                    record(RecordKind::Polarizer, fmt::format("known_r{}_{:.1f}deg", rep, a), a,
                           rep, std::nullopt),
                    synthetic_record_frame(cam, source, band, a, true, true, ++seed));
        }
        w.mark_complete();
    }
    {  // Field scene, with a shutter frame for the offset update.
        SessionManifest m = base;
        m.metadata = {{"site", "field"}, {"polarizer_in_beam", true}};
        auto w = SessionWriter::create(root / "scene", m);
        w.add_record(
            record(RecordKind::Shutter, "shutter", 0.0, 0, 293.15),
            synthetic_record_frame(cam, uniform_scene(cam.width, cam.height, band.radiance(293.15)),
                                   band, 0.0, false, true, ++seed));
        for (double a : cam.angles_deg)
            w.add_record(record(RecordKind::Polarizer, fmt::format("scene_{:.1f}deg", a), a, 0,
                                std::nullopt),
                         synthetic_record_frame(cam, scene, band, a, true, true, ++seed));
        w.mark_complete();
    }
}

Image synthetic_panel_scene(int width, int height, const Band& band) {
    Image s(width, height);
    auto& s0 = s.add_channel("S0", static_cast<float>(band.radiance(280.0)));
    auto& s1 = s.add_channel("S1");
    auto& s2 = s.add_channel("S2");
    const double l_dw = band.radiance(230.0), l_bb = band.radiance(300.0);
    for (int y = height / 6; y < height - height / 6; ++y)
        for (int x = 0; x < width; ++x) {
            const std::size_t i = s.index(x, y);
            if (x >= width / 16 && x < width / 4) {
                s0[i] = static_cast<float>(l_dw);  // IR reflector: sees the downwelling sky
            } else if (x >= 3 * width / 8 && x < 5 * width / 8) {
                s0[i] = static_cast<float>(0.07 * l_dw + 0.93 * l_bb);
                s1[i] = static_cast<float>(-0.035 * (l_bb - l_dw));
                s2[i] = static_cast<float>(0.01 * (l_bb - l_dw));
            }
        }
    return s;
}

}  // namespace tirpol::calibration
