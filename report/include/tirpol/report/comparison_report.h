#pragma once
/// \file comparison_report.h
/// The measured-vs-simulated comparison report: registration, side-by-side images with shared
/// colour scales, difference and z maps, per-region statistics, scatter plots and histograms,
/// written as a self-contained `report.html`, a `report.json` with every number (keys in
/// docs/report.md) and the PNGs, all under one directory with atomic writes.
///
/// Statistics of the angle of polarization (AoP) as an axial quantity: AoP and AoP + 180° are the
/// same state, so means and spreads are taken on the doubled angle (Mardia & Jupp, Directional
/// Statistics, 2000, §2.2 and §9.3.2: mean direction of axial data = half the mean of 2θ, circular
/// standard deviation √(−2 ln R̄)). Only pixels where both images are significantly polarized count:
/// elsewhere AoP is the angle of noise.
///
/// Per-region comparison statistics of a measured and a registered simulated quantity, and the
/// per-pixel normalised difference z = (m − s) / √(σ_m² + σ_s²): under the hypothesis that the
/// simulation is right and both noises are Gaussian, z ~ N(0, 1), so |z| > 2 in 4.55 % and |z| > 3
/// in 0.27 % of the pixels (two-sided normal tail probabilities, Abramowitz & Stegun 26.2).
///
/// The report's answer in one paragraph: which regions agree with the simulation within the noise,
/// which do not and in which quantity by how much, whether the measurement was calibrated over the
/// scene's radiances, what each part of a region mean's σ contains (measurement, render,
/// registration), and whether the verdicts have power (the smallest bias the tests detect, against
/// the simulated signal they test).

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "tirpol/core/image.h"
#include "tirpol/report/provenance.h"
#include "tirpol/report/regions.h"
#include "tirpol/report/registration.h"
#include "tirpol/report/verdict.h"

namespace tirpol::report {

/// Two-sided tail probabilities of the standard normal distribution, P(|z| > 2) and P(|z| > 3)
/// (Abramowitz & Stegun, Handbook of Mathematical Functions, table 26.1: erfc(2/√2), erfc(3/√2)).
inline constexpr double kNormalTailAbove2 = 0.045500263896358;
inline constexpr double kNormalTailAbove3 = 0.002699796063260;

/// Statistics of one quantity over the pixels of a region where both values are finite.
/// std is the population standard deviation (divide by n); bias = mean(m − s);
/// rmse = √mean((m − s)²). All zero with pixel_count = 0 when no pixel is valid.
struct QuantityStats {
    std::size_t pixel_count = 0;
    double measured_mean = 0.0, measured_std = 0.0;
    double simulated_mean = 0.0, simulated_std = 0.0;
    double bias = 0.0, rmse = 0.0;
    /// Standard error of `bias`: sample std of m − s over √n (pixels treated as independent).
    double bias_sigma = 0.0;
};

/// `measured`, `simulated` and `mask` have the same length; a pixel counts when mask ≠ 0 and both
/// values are finite.
QuantityStats quantity_stats(const std::vector<float>& measured,
                             const std::vector<float>& simulated,
                             const std::vector<std::uint8_t>& mask);

/// Mean of the finite values of `data` under `mask`; nullopt when there is none.
std::optional<double> masked_mean(const std::vector<float>& data,
                                  const std::vector<std::uint8_t>& mask);

/// Per-pixel z = (m − s)/√(var_m + var_s); NaN where an input is not finite or the total variance
/// is not positive. A variance estimated from few samples (a Monte-Carlo render's per-pixel
/// variance has replicates − 1 degrees of freedom, its `variance_dof`) makes that ratio Student-t
/// distributed with heavier tails than a normal: with finite `measured_dof`/`simulated_dof` each z
/// is mapped to the normal value of the same two-sided tail probability under t with the
/// Welch–Satterthwaite degrees of freedom ν = (v_m + v_s)² / (v_m²/ν_m + v_s²/ν_s) (Welch 1947,
/// Biometrika 34, 28), so that |z| > 2 keeps meaning 4.55 % under noise alone. Infinite dof (the
/// default): the plain ratio.
std::vector<float> z_scores(const std::vector<float>& measured, const std::vector<float>& simulated,
                            const std::vector<float>& measured_variance,
                            const std::vector<float>& simulated_variance,
                            double measured_dof = std::numeric_limits<double>::infinity(),
                            double simulated_dof = std::numeric_limits<double>::infinity());

/// z_scores with a per-pixel `simulated_dof` (a variance pooled over each pixel's neighbourhood,
/// whose dof depends on the pixels pooled).
std::vector<float> z_scores(const std::vector<float>& measured, const std::vector<float>& simulated,
                            const std::vector<float>& measured_variance,
                            const std::vector<float>& simulated_variance, double measured_dof,
                            const std::vector<float>& simulated_dof);

/// The standard normal deviate with the same two-sided tail probability as `t` under Student's t
/// with `dof` degrees of freedom (sign kept); `t` itself for infinite dof.
double normal_equivalent_of_t(double t, double dof);

/// Summary of z over a region: fractions of valid pixels beyond 2 and 3, mean and RMS of z.
struct ZStats {
    std::size_t pixel_count = 0;
    double fraction_above_2 = 0.0, fraction_above_3 = 0.0;
    double mean = 0.0, rms = 0.0;
};
ZStats z_stats(const std::vector<float>& z, const std::vector<std::uint8_t>& mask);

/// True when the fraction of |z| > 2 does not exceed the normal expectation 4.55 % by more than
/// three binomial standard deviations √(p(1−p)/n): the differences are explained by the stated
/// noise. (Pixels are treated as independent; spatially correlated noise makes the test stricter
/// than it looks.)
bool consistent_with_noise(const ZStats& z);

/// Noise standard deviation of an image by Immerkær's method ("Fast noise variance estimation",
/// Computer Vision and Image Understanding 64(2), 1996, eq. 2): σ = √(π/2)/(6(W−2)(H−2)) Σ|I ∗ N|
/// with N the 3×3 difference of two Laplacians. Non-finite pixels and their neighbourhoods are
/// skipped.
double immerkaer_noise_sigma(const std::vector<float>& data, int width, int height);

/// Linear polarization |P| = √(S1² + S2²) is significant when it exceeds this many σ of its noise.
inline constexpr double kAopSignificanceSigma = 3.0;

struct AopStats {
    std::size_t region_pixel_count = 0;  ///< pixels in the region with finite S1, S2 in both images
    std::size_t pixel_count = 0;         ///< of those, significantly polarized in both images
    double measured_mean_deg = 0.0;      ///< axial mean AoP, [0, 180)
    double simulated_mean_deg = 0.0;     ///< axial mean AoP, [0, 180)
    double difference_mean_deg = 0.0;    ///< axial mean of AoP_m − AoP_s, [−90, 90)
    double difference_std_deg = 0.0;     ///< circular standard deviation of AoP_m − AoP_s (axial)
};

/// The linear-polarization planes of one image, per pixel: S1, S2 and their variances.
struct LinearPolarizationPlanes {
    const std::vector<float>& s1;
    const std::vector<float>& s2;
    const std::vector<float>& var_s1;
    const std::vector<float>& var_s2;
};

/// AoP statistics over `mask` from the planes of both images. A pixel counts when
/// √(S1² + S2²) > kAopSignificanceSigma · √((var_S1 + var_S2)/2) in both the measured and the
/// simulated image. All planes have the mask's length.
AopStats aop_stats(const LinearPolarizationPlanes& measured,
                   const LinearPolarizationPlanes& simulated,
                   const std::vector<std::uint8_t>& mask);

/// A quantity the report compares statistically (AoP is shown, not averaged: it is an angle
/// modulo 180°).
enum class Quantity { S0, S1, S2, DoLP };

/// Quantities compared statistically.
inline constexpr std::array<Quantity, 4> kComparedQuantities = {Quantity::S0, Quantity::S1,
                                                                Quantity::S2, Quantity::DoLP};
/// Quantities with a z statistic and a verdict (those that carry variances).
inline constexpr std::array<Quantity, 3> kZQuantities = {Quantity::S0, Quantity::S1, Quantity::S2};

/// "S0", "S1", "S2", "DoLP": the quantity's channel in the images and its key in report.json.
const std::string& quantity_name(Quantity quantity);

/// One value for each of S0, S1 and S2 (kZQuantities): every one is always there, so a reader
/// needs no lookup that can miss.
template <class T>
struct StokesValues {
    T s0{}, s1{}, s2{};

    /// The value of `quantity`; throws std::out_of_range for DoLP, which has none.
    T& operator[](Quantity quantity) { return *pick(this, quantity); }
    const T& operator[](Quantity quantity) const { return *pick(this, quantity); }

private:
    template <class Self>
    static auto pick(Self* self, Quantity quantity) {
        switch (quantity) {
            case Quantity::S0:
                return &self->s0;
            case Quantity::S1:
                return &self->s1;
            case Quantity::S2:
                return &self->s2;
            case Quantity::DoLP:
                break;
        }
        throw std::out_of_range("StokesValues: DoLP has no value (only S0, S1, S2)");
    }
};

/// One value for each compared quantity (kComparedQuantities): S0, S1, S2 and DoLP.
template <class T>
struct ComparedValues : StokesValues<T> {
    T dolp{};

    /// The value of `quantity`.
    T& operator[](Quantity quantity) {
        return quantity == Quantity::DoLP ? dolp : StokesValues<T>::operator[](quantity);
    }
    const T& operator[](Quantity quantity) const {
        return quantity == Quantity::DoLP ? dolp : StokesValues<T>::operator[](quantity);
    }
};

struct CompareOptions {
    RegistrationMethod registration = RegistrationMethod::Auto;
    std::vector<TiePoint> control_points;
    /// The measured camera's calibrated model, for RegistrationMethod::CameraModel, and its name
    /// (file).
    std::optional<CameraModel> camera_model;
    std::string camera_model_name = "camera model";
    /// Regions of interest in measured pixels; none = one region covering the image.
    std::optional<RegionSet> regions;
    /// Measured noise when the measured image has no S0_std/S1_std/S2_std (or *_var) channels: the
    /// radiance noise σ_I of one polarizer frame (NEDT × dL/dT), W/(m²·sr). With the four-angle
    /// reduction of paper eqs 14–16, σ(S0) = σ_I and σ(S1) = σ(S2) = √2 σ_I.
    std::optional<double> measured_frame_sigma;
    /// Measurement errors common to every pixel of a region (they do not average down over its
    /// pixels): a relative gain uncertainty (e.g. 0.005 from the blackbody's temperature and
    /// emissivity), which scales S0, S1 and S2, and an offset uncertainty of S0 in the units of S0
    /// (it cancels in S1, S2).
    double measured_gain_sigma_relative = 0.0;
    double measured_offset_sigma = 0.0;
    /// False-alarm rate per region and power of the region-mean test (verdict.h).
    TestDesign design;
    /// Names shown in the report and in error messages (usually the file paths).
    std::string measured_name = "measured";
    std::string simulated_name = "simulated";
    /// Spectral band [lo, hi] µm for the S0 bias in kelvin; default: the measured EXR's `band_um`
    /// attribute, else the simulated one's; without any, no kelvin bias is given.
    std::optional<std::array<double, 2>> band_um;
    /// Tool version, command line and input files shown in the report (filled by the CLI).
    Provenance provenance;
    /// Checked between the stages of compare() (before and after the registration, per compared
    /// quantity, per region): once set, compare() throws tirpol::Cancelled. Null: never.
    const std::atomic<bool>* cancel = nullptr;
};

/// S0 bias as a brightness-temperature difference: bias / (dL/dT) at the brightness temperature of
/// the simulated mean S0, with the standard error of the mean difference carried the same way.
struct KelvinBias {
    double temperature_k = 0.0;  ///< brightness temperature of the simulated mean S0
    double radiance_dT = 0.0;    ///< dL/dT of the band at temperature_k, W/(m²·sr·K)
    double bias_k = 0.0;
    double bias_sigma_k = 0.0;
};

/// Where the measured σ of one quantity came from, and its typical value.
struct NoiseSource {
    std::string measured;  ///< "channel S1_std", "--measured-sigma", "flat region 'bg'", "Immerkaer
                           ///< estimate"
    std::string simulated;  ///< "channel S1_var" or "none (σ_s = 0)"
    double measured_sigma_median = 0.0;
    double simulated_sigma_median = 0.0;
    /// Degrees of freedom of each variance, as the z statistic uses them: the image's
    /// `variance_dof` attribute (a render: replicates − 1); infinite where the image states none
    /// (a variance taken as exact). Below 9 the z maps pool the simulated variance over each
    /// pixel's neighbourhood (`simulated` says so).
    double measured_dof = std::numeric_limits<double>::infinity();
    double simulated_dof = std::numeric_limits<double>::infinity();
    /// The measured σ is one estimate for all pixels (a flat region's scatter), not a per-pixel
    /// one.
    bool measured_shared = false;
};

struct RegionResult {
    std::string name;
    std::size_t pixel_count = 0;          ///< pixels inside the polygon
    ComparedValues<QuantityStats> stats;  ///< S0, S1, S2, DoLP
    /// mean S1(region) − mean S1(background), W/(m²·sr); absent without a background region.
    std::optional<double> s1_contrast_measured, s1_contrast_simulated;
    StokesValues<ZStats> z;  ///< z = (m − s)/σ of S0, S1, S2
    ZStats z_pooled;         ///< S0, S1 and S2 pooled (report.json's "all"), for reference only
    /// Of S0, S1, S2: the region-mean agreement test and the per-pixel σ diagnostic.
    StokesValues<QuantityVerdict> verdicts;
    Agreement verdict = Agreement::NoData;  ///< ExceedsNoise when any quantity's mean test exceeds
    AopStats aop;                           ///< AoP over significantly polarized pixels
    std::optional<KelvinBias> s0_bias_k;    ///< absent without a band or a positive simulated S0
};

/// The measured image's radiometric calibration range (attributes written by the calibration's
/// reduction): the fraction of the reduced frames' good pixels whose radiance lay outside the
/// blackbody set-points' radiance range, i.e. was extrapolated.
struct CalibrationRange {
    double outside_fraction = 0.0;  ///< largest over the reduced frames, 0..1
    double lo_k = 0.0, hi_k = 0.0;  ///< blackbody set-points, lowest and highest
};

struct CompareResult {
    int width = 0, height = 0;  ///< measured (and comparison) grid
    int simulated_width = 0, simulated_height = 0;
    std::string units;  ///< of S0, S1, S2
    Registration registration;
    StokesValues<NoiseSource> noise;  ///< of S0, S1, S2
    std::vector<RegionResult> regions;
    std::string background;                   ///< background region name or empty
    std::filesystem::path html, json;         ///< written files
    std::vector<std::filesystem::path> pngs;  ///< image figures
    std::vector<std::filesystem::path>
        svgs;                        ///< plots (scatter, histograms), also inlined in the page
    std::vector<std::string> notes;  ///< warnings shown in the report (e.g. no simulation variance)
    std::optional<CalibrationRange>
        calibration_range;  ///< absent when the measured image does not say
    TestDesign design;      ///< of the region-mean tests
    /// What the σ of each side contains, in words (for the Summary and report.json).
    std::string measured_sigma_contains, simulated_sigma_contains;
    /// Colour-scale limits [min, max] of the figures: "S0" (shared by measured and simulated),
    /// "S0_difference", …, "z"; in the units of the quantity.
    std::map<std::string, std::array<double, 2>> colour_scales;
    std::filesystem::path exr;  ///< comparison.exr: full-resolution planes behind the figures
    std::optional<std::array<double, 2>> band_um;  ///< band used for the kelvin bias
    std::string band_source;  ///< "--band-um", "measured band_um attribute", …
    Provenance provenance;
};

/// The planes behind the numbers and figures, on the measured grid.
struct ComparisonPlanes {
    Image measured,
        simulated;  ///< simulated registered; both with DoLP and AoP derived from S0..S2
    std::map<std::string, std::vector<float>>
        difference;                               ///< S0, S1, S2, DoLP, AoP (AoP wrapped to ±90°)
    std::map<std::string, std::vector<float>> z;  ///< S0, S1, S2
    std::map<std::string, std::vector<float>> total_variance;  ///< σ_m² + σ_s² of S0, S1, S2
    std::vector<Region> regions;
    std::vector<std::vector<std::uint8_t>> masks;  ///< one per region
};

struct Comparison {
    CompareResult result;  ///< every number (file paths empty until written)
    ComparisonPlanes planes;
};

/// Checks that `image` has S0, S1 and S2; throws tirpol::Error "<name>: <role> Stokes image lacks
/// channel(s) …; channels present: …" otherwise.
void require_stokes_channels(const Image& image, const std::string& name, const std::string& role);

/// Compares `measured` with `simulated`: registration, statistics, verdicts; writes nothing. Throws
/// tirpol::Error for missing channels, bad regions, or a registration that is impossible without
/// control points.
Comparison compare(const Image& measured, const Image& simulated, const CompareOptions& options);

/// Writes report.html, report.json, comparison.exr and the figures of `comparison` into
/// `report_dir` (created if needed) and records their paths in comparison.result.
void write_report(Comparison& comparison, const CompareOptions& options,
                  const std::filesystem::path& report_dir);

/// compare() then write_report(): compares `measured` with `simulated` and writes report.html,
/// report.json and the PNGs into `report_dir` (created if needed). Returns every number written.
/// Throws tirpol::Error for missing channels, bad regions, or a registration that is impossible
/// without control points.
CompareResult write_comparison_report(const Image& measured, const Image& simulated,
                                      const CompareOptions& options,
                                      const std::filesystem::path& report_dir);

/// report.json's content for `result` (pretty-printed), as written by write_comparison_report.
std::string comparison_json(const CompareResult& result);

/// `tirpol compare`: files by path and the values of its options.
struct ComparisonRunOptions {
    std::string measured, simulated;  ///< Stokes EXRs
    /// Regions YAML, control points YAML, camera model YAML; empty: none.
    std::string regions, control_points, camera_model;
    /// none | auto | control-points | camera-model; empty: camera-model with a camera model, else
    /// control-points with control points, else auto.
    std::string registration;
    std::optional<double> measured_frame_sigma;  ///< CompareOptions::measured_frame_sigma
    double gain_sigma_relative = 0.0, offset_sigma = 0.0;
    double false_alarm = 0.05, power = 0.80;  ///< TestDesign
    std::vector<double> band_um;              ///< empty or LO HI, µm
    std::string output;                       ///< report directory
    bool force = false;  ///< existing report files may be replaced (OutputGuard)
    std::string tool_version, command_line;  ///< for the provenance
};

/// Checks the option values (tirpol::OptionValueError naming the option) and the outputs
/// (OutputGuard), reads the files, records them in the provenance and writes the report
/// (write_comparison_report).
CompareResult run_comparison(const ComparisonRunOptions& options);

/// Whether the region-mean test of `quantity` (S0, S1 or S2) in `region` has power: its detectable
/// bias is smaller than the magnitude of the simulated region mean it tests. Without power a
/// simulation that predicted zero would read "consistent with noise" as well, so "consistent" says
/// little. False for a quantity without data, and for DoLP, which has no test.
bool verdict_has_power(const RegionResult& region, Quantity quantity);

/// Plain UTF-8 text (no markup), one paragraph of a few sentences; read from `result` only.
std::string summary_paragraph(const CompareResult& result);

/// What `tirpol compare` prints: the registration and its residual, the summary paragraph, one
/// table row per region (pixels, S0 bias in kelvin, each quantity's t of the means with its
/// detectable bias and verdict; columns padded by displayed width), the notes and the report path.
std::string comparison_text(const CompareResult& result);

}  // namespace tirpol::report
