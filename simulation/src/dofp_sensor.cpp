#include "tirpol/simulation/dofp_sensor.h"

#include <algorithm>
#include <cmath>

#include "rng.h"
#include "temperature_value.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/geometry.h"

namespace tirpol::simulation {

namespace {

/// Independent draws per (pixel, quantity): the manufacturing draw and each frame's noise are
/// separate streams of the counter-based generator, so a pixel's parameters do not depend on the
/// image size or on how many frames were read.
enum Stream : std::uint64_t {
    kAxis = 1,
    kDiattenuation,
    kTransmission,
    kResponsivity,
    kOffset,
    kNoiseBase = 1000,
};

double standard_normal(std::uint64_t seed, std::uint64_t pixel, std::uint64_t stream) {
    SampleStream rng(seed, pixel, stream);
    const double u1 = 1.0 - rng.next(), u2 = rng.next();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * kPi * u2);
}

void require(bool ok, const std::string& context, const std::string& what) {
    if (!ok) fail("{}: {}", context, what);
}

}  // namespace

void DofpSensorSpec::validate(const std::string& context) const {
    for (std::size_t k = 0; k < 4; ++k) {
        require(std::isfinite(pattern_deg[k]) && pattern_deg[k] >= 0.0 && pattern_deg[k] < 180.0,
                context,
                fmt::format("pattern_deg[{}] = {} is not an angle in [0, 180) degrees", k,
                            pattern_deg[k]));
        for (std::size_t j = 0; j < k; ++j)
            require(std::abs(pattern_deg[k] - pattern_deg[j]) > 0.01, context,
                    fmt::format("pattern_deg[{}] and [{}] are both {}°: the four analyzers must "
                                "differ",
                                j, k, pattern_deg[k]));
    }
    const DofpManufacturingSpread& s = spread;
    require(s.axis_sigma_deg >= 0.0 && s.axis_sigma_deg <= 45.0, context,
            "spread.axis_sigma_deg must be in [0, 45]");
    require(s.diattenuation_mean > 0.0 && s.diattenuation_mean <= 1.0, context,
            "spread.diattenuation_mean must be in (0, 1]");
    require(s.diattenuation_sigma >= 0.0 && s.diattenuation_sigma <= 1.0, context,
            "spread.diattenuation_sigma must be in [0, 1]");
    require(s.transmission_mean > 0.0 && s.transmission_mean <= 1.0, context,
            "spread.transmission_mean must be in (0, 1]");
    require(s.transmission_rel_sigma >= 0.0 && s.transmission_rel_sigma <= 1.0, context,
            "spread.transmission_rel_sigma must be in [0, 1]");
    require(s.responsivity_rel_sigma >= 0.0 && s.responsivity_rel_sigma <= 1.0, context,
            "spread.responsivity_rel_sigma must be in [0, 1]");
    require(s.offset_sigma_counts >= 0.0 && std::isfinite(s.offset_sigma_counts), context,
            "spread.offset_sigma_counts must be ≥ 0");
    require(
        responsivity_counts_per_radiance > 0.0 && std::isfinite(responsivity_counts_per_radiance),
        context, "responsivity_counts_per_radiance must be > 0");
    require(std::isfinite(offset_counts), context, "offset_counts must be finite");
    require(nedt_k >= 0.0 && nedt_k <= 100.0, context, "nedt_k must be in [0, 100]");
    require(reference_temperature_k > 0.0, context, "reference_temperature must be > 0 K");
    require(bits_per_pixel >= 8 && bits_per_pixel <= 16, context,
            fmt::format("bits_per_pixel = {} is not in [8, 16]", bits_per_pixel));
}

DofpSensorSpec DofpSensorSpec::from_config(const ConfigNode& node) {
    node.check_keys({"pattern_deg", "spread", "responsivity_counts_per_radiance", "offset_counts",
                     "nedt_k", "reference_temperature", "bits_per_pixel", "seed"});
    DofpSensorSpec s;
    if (node.has("pattern_deg")) {
        const auto angles = node.get<std::vector<double>>("pattern_deg");
        if (angles.size() != 4)
            node.at("pattern_deg")
                .fail(fmt::format("expected 4 angles (cells (0,0) (0,1) (1,0) (1,1)), got {}",
                                  angles.size()));
        std::copy(angles.begin(), angles.end(), s.pattern_deg.begin());
    }
    if (auto sp = node.find("spread")) {
        sp->check_keys({"axis_sigma_deg", "diattenuation_mean", "diattenuation_sigma",
                        "transmission_mean", "transmission_rel_sigma", "responsivity_rel_sigma",
                        "offset_sigma_counts"});
        DofpManufacturingSpread& m = s.spread;
        if (sp->has("axis_sigma_deg")) m.axis_sigma_deg = sp->get_in_range("axis_sigma_deg", 0, 45);
        if (sp->has("diattenuation_mean"))
            m.diattenuation_mean = sp->get_in_range("diattenuation_mean", 1e-6, 1.0);
        if (sp->has("diattenuation_sigma"))
            m.diattenuation_sigma = sp->get_in_range("diattenuation_sigma", 0.0, 1.0);
        if (sp->has("transmission_mean"))
            m.transmission_mean = sp->get_in_range("transmission_mean", 1e-6, 1.0);
        if (sp->has("transmission_rel_sigma"))
            m.transmission_rel_sigma = sp->get_in_range("transmission_rel_sigma", 0.0, 1.0);
        if (sp->has("responsivity_rel_sigma"))
            m.responsivity_rel_sigma = sp->get_in_range("responsivity_rel_sigma", 0.0, 1.0);
        if (sp->has("offset_sigma_counts"))
            m.offset_sigma_counts = sp->get_in_range("offset_sigma_counts", 0.0, 1e6);
    }
    if (node.has("responsivity_counts_per_radiance"))
        s.responsivity_counts_per_radiance =
            node.get_in_range("responsivity_counts_per_radiance", 1e-9, 1e9);
    if (node.has("offset_counts")) s.offset_counts = node.get_in_range("offset_counts", -1e6, 1e6);
    if (node.has("nedt_k")) s.nedt_k = node.get_in_range("nedt_k", 0.0, 100.0);
    if (node.has("reference_temperature"))
        s.reference_temperature_k = temperature_k_from_config(node.at("reference_temperature"));
    if (node.has("bits_per_pixel")) {
        const int bits = node.get<int>("bits_per_pixel");
        if (bits < 8 || bits > 16) node.at("bits_per_pixel").fail("expected 8 … 16 bits");
        s.bits_per_pixel = bits;
    }
    const int seed = node.get_or("seed", 1);
    if (seed < 0) node.at("seed").fail("expected a non-negative seed");
    s.seed = static_cast<std::uint64_t>(seed);
    s.validate("dofp sensor");
    return s;
}

std::array<double, 3> DofpPixels::analysis(std::size_t i) const {
    const double g = responsivity[i] * 0.5 * transmission[i];
    const double two_theta = 2.0 * axis_deg[i] * (kPi / 180.0);
    return {g, g * diattenuation[i] * std::cos(two_theta),
            g * diattenuation[i] * std::sin(two_theta)};
}

DofpSensor::DofpSensor(DofpSensorSpec spec, int width, int height, Band band)
    : m_spec(std::move(spec)), m_band(std::move(band)) {
    m_spec.validate("dofp sensor");
    if (width < 2 || height < 2 || width % 2 != 0 || height % 2 != 0)
        fail(
            "dofp sensor: the focal plane is {}×{}; a 2×2 microgrid needs an even width and "
            "height ≥ 2",
            width, height);
    m_pixels.width = width;
    m_pixels.height = height;
    const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    for (auto* plane : {&m_pixels.axis_deg, &m_pixels.diattenuation, &m_pixels.transmission,
                        &m_pixels.responsivity, &m_pixels.offset_counts})
        plane->resize(n);
    const DofpManufacturingSpread& s = m_spec.spread;
    const std::uint64_t seed = m_spec.seed;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                                  static_cast<std::size_t>(x);
            m_pixels.axis_deg[i] =
                nominal_angle_deg(x, y) + s.axis_sigma_deg * standard_normal(seed, i, kAxis);
            m_pixels.diattenuation[i] =
                std::clamp(s.diattenuation_mean +
                               s.diattenuation_sigma * standard_normal(seed, i, kDiattenuation),
                           0.0, 1.0);
            m_pixels.transmission[i] = std::max(
                0.0, s.transmission_mean * (1.0 + s.transmission_rel_sigma *
                                                      standard_normal(seed, i, kTransmission)));
            m_pixels.responsivity[i] = std::max(
                0.0,
                m_spec.responsivity_counts_per_radiance *
                    (1.0 + s.responsivity_rel_sigma * standard_normal(seed, i, kResponsivity)));
            m_pixels.offset_counts[i] =
                m_spec.offset_counts + s.offset_sigma_counts * standard_normal(seed, i, kOffset);
        }
    m_noise_sigma_counts = m_spec.responsivity_counts_per_radiance * 0.5 * s.transmission_mean *
                           m_spec.nedt_k * m_band.radiance_dT(m_spec.reference_temperature_k);
}

double DofpSensor::nominal_angle_deg(int x, int y) const {
    return m_spec.pattern_deg[static_cast<std::size_t>(2 * (y % 2) + (x % 2))];
}

std::vector<float> DofpSensor::expected_counts(const Image& stokes) const {
    if (stokes.width() != width() || stokes.height() != height())
        fail("dofp sensor: the Stokes image is {}×{}, the focal plane {}×{}", stokes.width(),
             stokes.height(), width(), height());
    for (const char* c : {"S0", "S1", "S2"})
        if (!stokes.has_channel(c))
            fail("dofp sensor: the Stokes image has no channel {} (expected S0 S1 S2)", c);
    const auto& s0 = stokes.channel("S0");
    const auto& s1 = stokes.channel("S1");
    const auto& s2 = stokes.channel("S2");
    std::vector<float> counts(s0.size());
    for (std::size_t i = 0; i < counts.size(); ++i) {
        const auto w = m_pixels.analysis(i);
        counts[i] = static_cast<float>(w[0] * s0[i] + w[1] * s1[i] + w[2] * s2[i] +
                                       m_pixels.offset_counts[i]);
    }
    return counts;
}

Image DofpSensor::frame(const Image& stokes, std::uint64_t frame_index) const {
    std::vector<float> counts = expected_counts(stokes);
    const double full_scale = std::ldexp(1.0, m_spec.bits_per_pixel) - 1.0;
    for (std::size_t i = 0; i < counts.size(); ++i) {
        const double noise =
            m_noise_sigma_counts > 0.0
                ? m_noise_sigma_counts * standard_normal(m_spec.seed, i, kNoiseBase + frame_index)
                : 0.0;
        counts[i] = static_cast<float>(
            std::clamp(std::round(static_cast<double>(counts[i]) + noise), 0.0, full_scale));
    }
    Image out(width(), height());
    out.set_channel("counts", std::move(counts));
    out.attributes()["microgrid_pattern_deg"] =
        std::vector<double>(m_spec.pattern_deg.begin(), m_spec.pattern_deg.end());
    out.attributes()["frame_index"] = static_cast<int>(frame_index);
    out.attributes()["counts_noise_sigma"] = m_noise_sigma_counts;
    write_stokes_image_header(out, {.units = "counts: DN"});
    return out;
}

}  // namespace tirpol::simulation
