// The DoFP (microgrid) sensor stage: every pixel follows Malus's law through its own planted
// micro-polarizer; what the raw frames encode, fitted back pixel by pixel from frames of uniform
// polarized scenes, is the planted axis, diattenuation, gain and offset; the manufacturing draw has
// the stated statistics and is reproducible; the temporal noise is the NEDT's; and the IFOV error
// (false polarization at an unpolarized edge) comes out of a full-resolution render.

#include "tirpol/simulation/dofp_sensor.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "scene_fixtures.h"
#include "test_support.h"
#include "tirpol/core/error.h"
#include "tirpol/simulation/renderer.h"

namespace tirpol::simulation {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
/// A black Lambertian emitter: its pixels are exactly L_bb(T), free of Monte Carlo noise.
constexpr const char* kBlack =
    "{name: black, source: \"test\", model: lambertian, parameters: {reflectance: 0.0}}";

Image uniform_stokes(int w, int h, double s0, double s1, double s2) {
    Image img(w, h);
    img.add_channel("S0", static_cast<float>(s0));
    img.add_channel("S1", static_cast<float>(s1));
    img.add_channel("S2", static_cast<float>(s2));
    img.add_channel("S3", 0.0f);
    return img;
}

/// A uniform source of radiance L fully polarized at φ: S = L(1, cos 2φ, sin 2φ).
Image polarized_source(int w, int h, double radiance, double phi_deg) {
    return uniform_stokes(w, h, radiance, radiance * std::cos(2.0 * phi_deg * kDeg),
                          radiance * std::sin(2.0 * phi_deg * kDeg));
}

double sample_std(const std::vector<double>& v, double* mean_out = nullptr) {
    double mean = 0.0;
    for (double x : v) mean += x;
    mean /= static_cast<double>(v.size());
    double ss = 0.0;
    for (double x : v) ss += (x - mean) * (x - mean);
    if (mean_out) *mean_out = mean;
    return std::sqrt(ss / static_cast<double>(v.size() - 1));
}

TEST(DofpSensor, IdealPixelsFollowMalusLaw) {
    // No spread, ideal polarizers (d = 1, t = 1): a pixel with analyzer θ behind a fully polarized
    // source at φ reads R·L·cos²(φ − θ) above its offset (Malus's law).
    DofpSensorSpec spec;
    spec.spread = {0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.0};
    spec.nedt_k = 0.0;
    const DofpSensor sensor(spec, 4, 4, Band(8.0, 14.0));
    const double radiance = 30.0, r = spec.responsivity_counts_per_radiance;
    for (double phi = 0.0; phi < 180.0; phi += 15.0) {
        const auto counts = sensor.expected_counts(polarized_source(4, 4, radiance, phi));
        for (int y = 0; y < 4; ++y)
            for (int x = 0; x < 4; ++x) {
                const double theta = sensor.nominal_angle_deg(x, y);
                const double c = std::cos((phi - theta) * kDeg);
                EXPECT_NEAR(counts[static_cast<std::size_t>(y * 4 + x)] - spec.offset_counts,
                            r * radiance * c * c, 1e-3)
                    << "φ " << phi << " at (" << x << ", " << y << ")";
            }
    }
    // The Sony layout: (0,0) = 90°, (0,1) = 45°, (1,0) = 135°, (1,1) = 0°.
    EXPECT_EQ(sensor.nominal_angle_deg(0, 0), 90.0);
    EXPECT_EQ(sensor.nominal_angle_deg(1, 0), 45.0);
    EXPECT_EQ(sensor.nominal_angle_deg(0, 1), 135.0);
    EXPECT_EQ(sensor.nominal_angle_deg(3, 3), 0.0);
}

TEST(DofpSensor, RawFramesEncodeThePlantedAnalyzersAndNonUniformity) {
    // What the camera's frames say about each pixel, measured the way a lab would (dark frame →
    // offset; unpolarized flat field → gain; a polarizer turned through 12 angles → the Malus
    // cosine's phase and depth), against the planted truth. Noise off; the ADC's rounding
    // (≤ 0.5 count of ~10 000) is the only error.
    DofpSensorSpec spec;
    spec.spread.axis_sigma_deg = 2.0;
    spec.spread.diattenuation_sigma = 0.03;
    spec.nedt_k = 0.0;
    const int w = 16, h = 12;
    const DofpSensor sensor(spec, w, h, Band(8.0, 14.0));
    const double radiance = 30.0;
    const auto dark = sensor.frame(uniform_stokes(w, h, 0.0, 0.0, 0.0), 0).channel("counts");
    const auto flat = sensor.frame(uniform_stokes(w, h, radiance, 0.0, 0.0), 1).channel("counts");
    const int n_angles = 12;
    std::vector<std::vector<float>> turned;
    for (int k = 0; k < n_angles; ++k)
        turned.push_back(sensor.frame(polarized_source(w, h, radiance, 180.0 * k / n_angles), 2)
                             .channel("counts"));
    const DofpPixels& truth = sensor.pixels();
    double worst_axis = 0.0, worst_d = 0.0, worst_g = 0.0, worst_o = 0.0;
    for (std::size_t i = 0; i < dark.size(); ++i) {
        // I(φ) − o = g·L·(1 + d cos 2(φ − θ)): equally spaced φ over 180° make the Fourier sums
        // exact least squares.
        double a = 0.0, b = 0.0, c = 0.0;
        for (int k = 0; k < n_angles; ++k) {
            const double two_phi = 2.0 * (180.0 * k / n_angles) * kDeg;
            const double v = turned[static_cast<std::size_t>(k)][i] - dark[i];
            a += v / n_angles;
            b += 2.0 * v * std::cos(two_phi) / n_angles;
            c += 2.0 * v * std::sin(two_phi) / n_angles;
        }
        const double gain = (flat[i] - dark[i]) / radiance;
        const double d = std::hypot(b, c) / a;
        double axis = 0.5 * std::atan2(c, b) / kDeg;
        double axis_err = axis - truth.axis_deg[i];
        axis_err -= 180.0 * std::round(axis_err / 180.0);
        const double planted_gain = truth.responsivity[i] * 0.5 * truth.transmission[i];
        worst_axis = std::max(worst_axis, std::abs(axis_err));
        worst_d = std::max(worst_d, std::abs(d - truth.diattenuation[i]));
        worst_g = std::max(worst_g, std::abs(gain / planted_gain - 1.0));
        worst_o = std::max(worst_o, std::abs(dark[i] - truth.offset_counts[i]));
        // The planted analysis vector is what calibration fits: g·(1, d cos 2θ, d sin 2θ).
        const auto wv = truth.analysis(i);
        EXPECT_NEAR(b / radiance, wv[1], 2e-3 * wv[0]);
        EXPECT_NEAR(c / radiance, wv[2], 2e-3 * wv[0]);
    }
    EXPECT_LT(worst_axis, 0.01);  // degrees
    EXPECT_LT(worst_d, 2e-4);
    EXPECT_LT(worst_g, 1e-4);
    EXPECT_LE(worst_o, 0.5);
    // The spread is real: the planted axes differ from the nominal pattern.
    double max_dev = 0.0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            max_dev =
                std::max(max_dev, std::abs(truth.axis_deg[static_cast<std::size_t>(y * w + x)] -
                                           sensor.nominal_angle_deg(x, y)));
    EXPECT_GT(max_dev, 2.0);
}

TEST(DofpSensor, ManufacturingSpreadHasTheStatedStatisticsAndIsReproducible) {
    DofpSensorSpec spec;
    spec.spread = {1.5, 0.9, 0.02, 0.8, 0.1, 0.05, 120.0};
    const int w = 128, h = 128;
    const DofpSensor sensor(spec, w, h, Band(8.0, 14.0));
    const DofpPixels& p = sensor.pixels();
    std::vector<double> axis_err, rel_t, rel_r;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const std::size_t i = static_cast<std::size_t>(y * w + x);
            axis_err.push_back(p.axis_deg[i] - sensor.nominal_angle_deg(x, y));
            rel_t.push_back(p.transmission[i] / 0.8 - 1.0);
            rel_r.push_back(p.responsivity[i] / spec.responsivity_counts_per_radiance - 1.0);
        }
    // 16 384 draws: the sample σ is within ~1 % (1/√(2n)) of the stated one; 4 % is > 3σ.
    double mean = 0.0;
    EXPECT_NEAR(sample_std(axis_err, &mean), 1.5, 0.04 * 1.5);
    EXPECT_NEAR(mean, 0.0, 0.05);
    EXPECT_NEAR(sample_std(p.diattenuation, &mean), 0.02, 0.04 * 0.02);
    EXPECT_NEAR(mean, 0.9, 0.001);
    EXPECT_NEAR(sample_std(rel_t), 0.1, 0.004);
    EXPECT_NEAR(sample_std(rel_r), 0.05, 0.002);
    EXPECT_NEAR(sample_std(p.offset_counts, &mean), 120.0, 0.04 * 120.0);
    EXPECT_NEAR(mean, spec.offset_counts, 4.0);

    const DofpSensor again(spec, w, h, Band(8.0, 14.0));
    EXPECT_EQ(again.pixels().axis_deg, p.axis_deg) << "same seed: same array";
    EXPECT_EQ(again.pixels().offset_counts, p.offset_counts);
    spec.seed = 2;
    const DofpSensor other(spec, w, h, Band(8.0, 14.0));
    EXPECT_NE(other.pixels().axis_deg, p.axis_deg) << "another seed: another array";
}

TEST(DofpSensor, TemporalNoiseIsTheNedtsAndFreshPerFrame) {
    DofpSensorSpec spec;  // NEDT 50 mK at 300 K
    const int w = 64, h = 64;
    const Band band(8.0, 14.0);
    const DofpSensor sensor(spec, w, h, band);
    const double expected_sigma = spec.responsivity_counts_per_radiance * 0.5 *
                                  spec.spread.transmission_mean * 0.05 * band.radiance_dT(300.0);
    EXPECT_NEAR(sensor.noise_sigma_counts(), expected_sigma, 1e-9 * expected_sigma);
    const Image scene = uniform_stokes(w, h, band.radiance(300.0), 0.0, 0.0);
    const auto a = sensor.frame(scene, 5).channel("counts");
    const auto b = sensor.frame(scene, 6).channel("counts");
    EXPECT_EQ(sensor.frame(scene, 5).channel("counts"), a) << "a frame index is one realisation";
    std::vector<double> diff;
    for (std::size_t i = 0; i < a.size(); ++i) diff.push_back((a[i] - b[i]) / std::sqrt(2.0));
    // 4096 differences: σ within 1.1 % (1σ); rounding adds 1/12 count² (negligible at σ ≈ 3).
    EXPECT_NEAR(sample_std(diff), expected_sigma, 0.05 * expected_sigma);
    EXPECT_GT(expected_sigma, 1.0);
}

TEST(DofpSensor, AdcClipsToItsBitDepth) {
    DofpSensorSpec spec;
    spec.bits_per_pixel = 12;
    spec.nedt_k = 0.0;
    const DofpSensor sensor(spec, 4, 4, Band(8.0, 14.0));
    const auto counts = sensor.frame(uniform_stokes(4, 4, 1000.0, 0.0, 0.0), 0).channel("counts");
    for (float c : counts) EXPECT_EQ(c, 4095.0f);
}

TEST(DofpSensor, BadSpecsAreRefusedNamingTheField) {
    DofpSensorSpec spec;
    spec.pattern_deg = {0.0, 45.0, 45.0, 135.0};
    EXPECT_THROW(
        {
            try {
                DofpSensor(spec, 4, 4, Band(8.0, 14.0));
            } catch (const Error& e) {
                EXPECT_NE(std::string(e.what()).find("pattern_deg"), std::string::npos);
                throw;
            }
        },
        Error);
    EXPECT_THROW(DofpSensor(DofpSensorSpec{}, 5, 4, Band(8.0, 14.0)), Error);
    const DofpSensor sensor(DofpSensorSpec{}, 4, 4, Band(8.0, 14.0));
    EXPECT_THROW(sensor.expected_counts(uniform_stokes(6, 4, 1, 0, 0)), Error);

    EXPECT_THROW(DofpSensorSpec::from_config(ConfigNode::parse("pattern_deg: [0, 45, 90]\n")),
                 Error);
    EXPECT_THROW(DofpSensorSpec::from_config(ConfigNode::parse("spread: {axis_sigma: 1}\n")),
                 Error);
    EXPECT_THROW(DofpSensorSpec::from_config(ConfigNode::parse("bits_per_pixel: 20\n")), Error);
    const DofpSensorSpec parsed = DofpSensorSpec::from_config(ConfigNode::parse(
        "pattern_deg: [0, 45, 90, 135]\nspread: {axis_sigma_deg: 0.5, diattenuation_mean: 0.9}\n"
        "bits_per_pixel: 12\nseed: 4\nreference_temperature: 290\n"));
    EXPECT_EQ(parsed.pattern_deg[1], 45.0);
    EXPECT_EQ(parsed.spread.axis_sigma_deg, 0.5);
    EXPECT_EQ(parsed.spread.diattenuation_mean, 0.9);
    EXPECT_EQ(parsed.bits_per_pixel, 12);
    EXPECT_EQ(parsed.seed, 4u);
}

TEST(DofpSensor, IfovErrorComesFromTheRenderedFootprints) {
    // An unpolarized scene (black Lambertian plates, seen along their normal, under a uniform sky)
    // with a warm plate in front of a cold one, their edge 0.3 pixel into a pixel column. Rendered
    // at the sensor's full resolution, each pixel holds the mean over its own footprint, so the
    // four analyzers of a cell across the edge see different radiances: super-pixel reduction shows
    // false polarization there, and none away from the edge, though no rendered pixel is polarized.
    tirpol::test::TempDir dir;
    const int n = 16;
    const double distance = 10.0, fov_deg = 10.0;
    const double pixel = 2.0 * distance * std::tan(0.5 * fov_deg * kDeg) / n;
    const double edge_x = 1.3 * pixel;  // column 9 (of 0…15) holds the edge, 0.3 of it warm
    const double warm_size = 50.0;
    const Scene scene = test::load_scene_text(
        dir,
        test::scene_header(n, n, 64, 2,
                           fmt::format("fov_deg: {}, position: [0, 0, {}], look_at: [0, 0, 0], "
                                       "up: [0, 1, 0]",
                                       fov_deg, distance),
                           "{type: uniform, temperature: 250}") +
            "objects:\n"
            "  - {name: back, geometry: {type: plane, size: [400, 400]}, material: " +
            kBlack +
            ", temperature: 280}\n"
            "  - {name: front, geometry: {type: plane, size: [" +
            fmt::format("{}, 400]}}, transform: {{translate: [{}, 0, 0.5]}}, material: ", warm_size,
                        edge_x - 0.5 * warm_size) +
            kBlack + ", temperature: 320}\n");
    const Image render_image = render(scene);
    const auto& s0 = render_image.channel("S0");
    const auto& s1 = render_image.channel("S1");
    const auto& s2 = render_image.channel("S2");
    for (std::size_t i = 0; i < s0.size(); ++i)
        ASSERT_LT(std::hypot(s1[i], s2[i]), 1e-3 * s0[i]) << "the rendered scene is unpolarized";

    DofpSensorSpec ideal;
    ideal.spread = {0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.0};
    ideal.nedt_k = 0.0;
    ideal.offset_counts = 0.0;
    ideal.responsivity_counts_per_radiance = 2.0;  // counts = S0 + S1 cos 2θ + S2 sin 2θ
    const DofpSensor sensor(ideal, n, n, scene.band);
    const auto counts = sensor.expected_counts(render_image);
    // The edge's pixel column: the one whose mean S0 lies between the two plates' (the Monte Carlo
    // noise of a pixel is ~1 %).
    int edge_column = -1;
    for (int x = 0; x < n; ++x) {
        double mean = 0.0;
        for (int y = 0; y < n; ++y) mean += s0[static_cast<std::size_t>(y * n + x)] / n;
        const double cold = scene.band.radiance(280.0), warm = scene.band.radiance(320.0);
        if (mean > cold + 0.1 * (warm - cold) && mean < warm - 0.1 * (warm - cold)) {
            EXPECT_EQ(edge_column, -1) << "one pixel column holds the edge";
            edge_column = x;
        }
    }
    ASSERT_GE(edge_column, 0);
    // Super-pixel reduction of the Sony layout: (0,0) 90°, (0,1) 45°, (1,0) 135°, (1,1) 0°.
    double edge_dolp = 1.0, elsewhere_dolp = 0.0;
    for (int cy = 0; cy < n / 2; ++cy)
        for (int cx = 0; cx < n / 2; ++cx) {
            auto index = [&](int dx, int dy) {
                return static_cast<std::size_t>((2 * cy + dy) * n + 2 * cx + dx);
            };
            const double i90 = counts[index(0, 0)], i45 = counts[index(1, 0)],
                         i135 = counts[index(0, 1)], i0 = counts[index(1, 1)];
            const double cs0 = 0.25 * (i0 + i45 + i90 + i135);
            const double dolp = std::hypot(0.5 * (i0 - i90), 0.5 * (i45 - i135)) / cs0;
            if (cx == edge_column / 2)
                edge_dolp = std::min(edge_dolp, dolp);
            else
                elsewhere_dolp = std::max(elsewhere_dolp, dolp);
        }
    std::printf("false DoLP: at least %.4f in the cells across the edge, at most %.4f elsewhere\n",
                edge_dolp, elsewhere_dolp);
    EXPECT_GT(edge_dolp, 0.05) << "the cells across the edge see two radiances";
    // Elsewhere only the render's Monte Carlo noise (~1 % per pixel at 64 spp) reaches the DoLP.
    EXPECT_LT(elsewhere_dolp, 0.02);
}

}  // namespace
}  // namespace tirpol::simulation
