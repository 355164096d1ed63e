#include "tirpol/simulation/sensor_model.h"

#include <cmath>

#include "rng.h"
#include "temperature_value.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/geometry.h"

namespace tirpol::simulation {

SensorModel SensorModel::from_config(const ConfigNode& node) {
    node.check_keys({"analyzer", "background", "counts", "seed"});
    SensorModel m;
    if (auto a = node.find("analyzer")) {
        a->check_keys({"angles_deg", "transmission", "extinction_ratio", "angle_offset_deg"});
        m.analyzer.angles_deg = a->get_or("angles_deg", m.analyzer.angles_deg);
        if (m.analyzer.angles_deg.empty())
            a->at("angles_deg").fail("expected at least one polarizer angle");
        if (a->has("transmission"))
            m.analyzer.transmission = a->get_in_range("transmission", 1e-6, 1.0);
        if (a->has("extinction_ratio"))
            m.analyzer.extinction_ratio = a->get_in_range("extinction_ratio", 1.0, 1e12);
        m.analyzer.angle_offset_deg = a->get_or("angle_offset_deg", 0.0);
    }
    if (auto b = node.find("background")) {
        b->check_keys({"reflectance", "reflected_radiance", "emissivity", "temperature"});
        if (b->has("reflectance"))
            m.background.reflectance = b->get_in_range("reflectance", 0.0, 1.0);
        if (b->has("reflected_radiance"))
            m.background.reflected_radiance = b->get_in_range("reflected_radiance", 0.0, 1e6);
        if (b->has("emissivity")) m.background.emissivity = b->get_in_range("emissivity", 0.0, 1.0);
        if (b->has("temperature"))
            m.background.temperature_k = temperature_k_from_config(b->at("temperature"));
    }
    if (auto c = node.find("counts")) {
        c->check_keys(
            {"gain_counts_per_radiance", "offset_counts", "nedt_k", "reference_temperature"});
        CountsModel cm;
        if (c->has("gain_counts_per_radiance"))
            cm.gain_counts_per_radiance = c->get_in_range("gain_counts_per_radiance", 1e-12, 1e12);
        cm.offset_counts = c->get_or("offset_counts", 0.0);
        if (c->has("nedt_k")) cm.nedt_k = c->get_in_range("nedt_k", 0.0, 100.0);
        if (c->has("reference_temperature"))
            cm.reference_temperature_k = temperature_k_from_config(c->at("reference_temperature"));
        m.counts = cm;
    }
    const int seed = node.get_or("seed", 1);
    if (seed < 0) node.at("seed").fail("expected a non-negative seed");
    m.seed = static_cast<std::uint64_t>(seed);
    return m;
}

WireGridPolarizer SensorModel::wire_grid(const Band& band) const {
    WireGridPolarizer grid;
    grid.transmission = analyzer.transmission;
    grid.extinction_ratio = analyzer.extinction_ratio;
    grid.angle_offset_deg = analyzer.angle_offset_deg;
    grid.reflectance = background.reflectance;
    grid.reflected_radiance = background.reflected_radiance;
    grid.emissivity = background.emissivity;
    grid.emitted_radiance = band.radiance(background.temperature_k);
    return grid;
}

std::vector<Image> polarizer_images(const Image& stokes, const SensorModel& model, const Band& band,
                                    std::uint64_t frame_index) {
    const auto& s0 = stokes.channel("S0");
    const auto& s1 = stokes.channel("S1");
    const auto& s2 = stokes.channel("S2");
    const auto& s3 = stokes.channel("S3");
    const WireGridPolarizer grid = model.wire_grid(band);
    double sigma_counts = 0.0;
    if (model.counts)
        sigma_counts = model.counts->gain_counts_per_radiance * model.counts->nedt_k *
                       band.radiance_dT(model.counts->reference_temperature_k);

    std::vector<Image> out;
    for (std::size_t ai = 0; ai < model.analyzer.angles_deg.size(); ++ai) {
        const double angle_deg = model.analyzer.angles_deg[ai];
        const AnalyzerAtAngle analyzer = analyzer_at(grid, angle_deg);
        Image img(stokes.width(), stokes.height());
        auto& radiance = img.add_channel("radiance");
        std::vector<float>* counts = model.counts ? &img.add_channel("counts") : nullptr;
        for (std::size_t i = 0; i < radiance.size(); ++i) {
            const double l = analyzer.radiance(StokesVector(s0[i], s1[i], s2[i], s3[i]));
            radiance[i] = static_cast<float>(l);
            if (!counts) continue;
            // Box–Muller on a counter-based stream: the same noise for the same (seed, frame,
            // angle, pixel).
            SampleStream rng(model.seed, (frame_index << 32) ^ i, ai);
            const double u1 = 1.0 - rng.next(), u2 = rng.next();
            const double gauss = std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * kPi * u2);
            (*counts)[i] = static_cast<float>(
                detector_counts(l, model.counts->gain_counts_per_radiance,
                                model.counts->offset_counts, sigma_counts, gauss));
        }
        if (model.counts) img.attributes()["counts_noise_sigma"] = sigma_counts;
        img.attributes()["polarizer_angle_deg"] = angle_deg;
        img.attributes()["frame_index"] = static_cast<int>(frame_index);
        write_stokes_image_header(img, {.units = "radiance: W/(m^2 sr); counts: DN"});
        out.push_back(std::move(img));
    }
    return out;
}

}  // namespace tirpol::simulation
