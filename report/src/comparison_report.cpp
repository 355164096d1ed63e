#include "tirpol/report/comparison_report.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "figures.h"
#include "html_report.h"
#include "pooled_variance.h"
#include "svg_plot.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/interrupt_signals.h"
#include "tirpol/core/radiometry.h"

namespace tirpol::report {

const std::string& quantity_name(Quantity quantity) {
    static const std::array<std::string, 4> names = {"S0", "S1", "S2", "DoLP"};
    return names.at(static_cast<std::size_t>(quantity));
}

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
using Mask = std::vector<std::uint8_t>;

std::string join(const std::vector<std::string>& items) {
    std::string out;
    for (const auto& item : items) out += (out.empty() ? "" : ", ") + item;
    return out.empty() ? "none" : out;
}

// DoLP and AoP (degrees, [0, 180)) from S0..S2, recomputed after resampling: interpolating an
// angle across its 0/180° wrap, or a ratio, would be wrong.
void derive_dolp_aop(Image& image) {
    const auto& s0 = image.channel("S0");
    const auto& s1 = image.channel("S1");
    const auto& s2 = image.channel("S2");
    std::vector<float> dolp(s0.size(), kNaN), aop(s0.size(), kNaN);
    for (std::size_t i = 0; i < s0.size(); ++i) {
        if (!std::isfinite(s0[i]) || !std::isfinite(s1[i]) || !std::isfinite(s2[i])) continue;
        dolp[i] = s0[i] > 0.0f ? std::hypot(s1[i], s2[i]) / s0[i] : 0.0f;
        double a = 0.5 * std::atan2(static_cast<double>(s2[i]), static_cast<double>(s1[i])) *
                   180.0 / std::numbers::pi;
        if (a < 0.0) a += 180.0;
        aop[i] = static_cast<float>(a);
    }
    image.set_channel("DoLP", std::move(dolp));
    image.set_channel("AoP", std::move(aop));
}

std::vector<float> difference(const std::vector<float>& m, const std::vector<float>& s,
                              bool angle) {
    std::vector<float> d(m.size());
    for (std::size_t i = 0; i < m.size(); ++i) {
        float v = m[i] - s[i];
        if (angle && std::isfinite(v)) v = std::remainder(v, 180.0f);  // AoP is defined modulo 180°
        d[i] = v;
    }
    return d;
}

// Variance plane of quantity `q` from a Q_std or Q_var channel, if the image has one.
std::optional<std::vector<float>> variance_channel(const Image& image, const std::string& q,
                                                   std::string& source) {
    if (image.has_channel(q + "_std")) {
        auto v = image.channel(q + "_std");
        for (auto& x : v) x *= x;
        source = "channel " + q + "_std";
        return v;
    }
    if (image.has_channel(q + "_var")) {
        source = "channel " + q + "_var";
        return image.channel(q + "_var");
    }
    return std::nullopt;
}

// Degrees of freedom of an image's variance channels (the renderer's `variance_dof`); infinite when
// the image does not say (a reduction's σ from many frames, or a model).
double variance_dof(const StokesImageHeader& header) {
    return header.variance_dof && *header.variance_dof > 0
               ? *header.variance_dof
               : std::numeric_limits<double>::infinity();
}

double median_sqrt(const std::vector<float>& variance) {
    std::vector<float> v;
    for (float x : variance)
        if (std::isfinite(x)) v.push_back(x);
    if (v.empty()) return 0.0;
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
    return std::sqrt(std::max(0.0f, v[v.size() / 2]));
}

std::pair<double, double> shared_range(const std::vector<float>& a, const std::vector<float>& b,
                                       const QuicklookOptions& options) {
    std::vector<float> both(a);
    both.insert(both.end(), b.begin(), b.end());
    return quicklook_range(both, options);
}

struct QuantityDisplay {
    std::string units;
    Colormap map;
};

// The two images' header attributes, read once.
struct Headers {
    StokesImageHeader measured, simulated;
};

// The band for the kelvin bias: the option, else the measured then the simulated `band_um`
// attribute.
std::optional<Band> comparison_band(const Headers& headers, const CompareOptions& options,
                                    CompareResult& result) {
    if (options.band_um) {
        result.band_um = options.band_um;
        result.band_source = "--band-um";
    } else if (const auto& m = headers.measured.band_um) {
        result.band_um = m;
        result.band_source = "band_um attribute of " + options.measured_name;
    } else if (const auto& s = headers.simulated.band_um) {
        result.band_um = s;
        result.band_source = "band_um attribute of " + options.simulated_name;
    } else {
        result.notes.push_back(
            "no spectral band (no band_um attribute in either image, no --band-um): the S0 bias "
            "is not converted to kelvin");
        return std::nullopt;
    }
    return Band((*result.band_um)[0], (*result.band_um)[1]);
}

std::optional<KelvinBias> kelvin_bias(const QuantityStats& s0, const Band& band) {
    if (s0.pixel_count == 0 || !(s0.simulated_mean > 0.0)) return std::nullopt;
    KelvinBias k;
    k.temperature_k = band.brightness_temperature(s0.simulated_mean);
    if (!std::isfinite(k.temperature_k)) return std::nullopt;
    k.radiance_dT = band.radiance_dT(k.temperature_k);
    k.bias_k = s0.bias / k.radiance_dT;
    k.bias_sigma_k = s0.bias_sigma / k.radiance_dT;
    return k;
}

// The calibration's range of a reduced Stokes image (calibration/session_calibration.cpp).
std::optional<CalibrationRange> calibration_range(const StokesImageHeader& measured) {
    if (!measured.calibration_range) return std::nullopt;
    const auto& [range_k, outside_fraction] = *measured.calibration_range;
    return CalibrationRange{outside_fraction, range_k[0], range_k[1]};
}

// What each side's σ holds, in words: the measured image's `std_includes` (written by the
// reduction) plus the common calibration terms given; the render's variance is Monte Carlo noise
// only.
void describe_sigma_contents(CompareResult& result, const Headers& headers,
                             const CompareOptions& options) {
    std::string m = headers.measured.std_includes.value_or("");
    if (m.empty()) m = "the measured image's σ channels or the noise estimate named per quantity";
    m += " (independent from pixel to pixel)";
    if (options.measured_gain_sigma_relative > 0.0 || options.measured_offset_sigma > 0.0)
        m += fmt::format(
            "; common to each region: calibration gain {:.3g} % and S0 offset {:.3g} {}",
            100.0 * options.measured_gain_sigma_relative, options.measured_offset_sigma,
            result.units);
    else
        m += "; no calibration error common to a region was given (gain/offset σ 0)";
    result.measured_sigma_contains = m;
    std::string s =
        "Monte Carlo noise of the render only, not errors of its model or inputs (materials, "
        "temperatures, sky, geometry)";
    if (const std::string note = headers.simulated.variance_note.value_or(""); !note.empty())
        s += "; " + note;
    result.simulated_sigma_contains = s;
}

std::size_t region_index(const std::vector<Region>& regions, const std::string& name) {
    for (std::size_t r = 0; r < regions.size(); ++r)
        if (regions[r].name == name) return r;
    return regions.size();
}

// The comparison's grid, units and regions; a bad polygon is reported before any expensive work.
Comparison start_comparison(const Image& measured, const Image& simulated,
                            const StokesImageHeader& measured_header,
                            const CompareOptions& options) {
    Comparison comparison;
    CompareResult& result = comparison.result;
    result.provenance = options.provenance;
    result.width = measured.width();
    result.height = measured.height();
    result.simulated_width = simulated.width();
    result.simulated_height = simulated.height();
    result.units = measured_header.units.value_or("W/(m²·sr)");
    std::vector<Region>& regions = comparison.planes.regions;
    if (options.regions) {
        regions = options.regions->regions;
        result.background = options.regions->background;
    } else {
        regions.push_back(whole_image_region(result.width, result.height));
    }
    for (const auto& region : regions)
        comparison.planes.masks.push_back(region_mask(region, result.width, result.height));
    return comparison;
}

// Registers the simulation onto the measured grid and derives DoLP and AoP on both.
void register_planes(Comparison& comparison, const Image& measured, const Image& simulated,
                     const CompareOptions& options) {
    CompareResult& result = comparison.result;
    throw_if_cancelled(options.cancel, "comparison");
    result.registration =
        options.registration == RegistrationMethod::CameraModel && options.camera_model
            ? register_by_camera_model(measured, simulated, *options.camera_model,
                                       options.camera_model_name)
            : register_images(measured, simulated, options.registration, options.control_points,
                              options.cancel);
    throw_if_cancelled(options.cancel, "comparison");
    comparison.planes.measured = measured;
    comparison.planes.simulated =
        resample_to_measured(simulated, result.registration, result.width, result.height);
    derive_dolp_aop(comparison.planes.measured);
    derive_dolp_aop(comparison.planes.simulated);
    if (std::abs(result.registration.rotation_deg) > 0.5)
        result.notes.push_back(
            fmt::format("the registration rotates the image by {:.2f}°; S1/S2 of the simulation "
                        "are not rotated back into the "
                        "measured frame, so their comparison is biased by that rotation",
                        result.registration.rotation_deg));
}

// Measured variance of quantity `q` when the image has no σ channel: the per-frame σ option, else
// the scatter in the flat noise region, else Immerkær's estimate.
std::vector<float> measured_variance_without_channel(const Comparison& comparison,
                                                     Quantity quantity,
                                                     const CompareOptions& options,
                                                     NoiseSource& noise) {
    const std::string& q = quantity_name(quantity);
    std::string& source = noise.measured;
    const Image& measured = comparison.planes.measured;
    const std::string noise_region_name =
        options.regions ? (options.regions->noise_region.empty() ? options.regions->background
                                                                 : options.regions->noise_region)
                        : std::string();
    double sigma = 0.0;
    if (options.measured_frame_sigma) {
        sigma = *options.measured_frame_sigma * (quantity == Quantity::S0 ? 1.0 : std::sqrt(2.0));
        source = fmt::format("--measured-sigma {:.4g} per frame (paper eqs 14–16)",
                             *options.measured_frame_sigma);
    } else if (!noise_region_name.empty()) {
        const auto& mask =
            comparison.planes.masks[region_index(comparison.planes.regions, noise_region_name)];
        const QuantityStats flat = quantity_stats(measured.channel(q), measured.channel(q), mask);
        sigma = flat.measured_std;
        source = "std of measured " + q + " in flat region '" + noise_region_name + "'";
        noise.measured_shared = true;
        noise.measured_dof =
            flat.pixel_count > 1 ? static_cast<double>(flat.pixel_count - 1) : kInfiniteDof;
    } else {
        sigma = immerkaer_noise_sigma(measured.channel(q), measured.width(), measured.height());
        source = "Immerkær noise estimate of measured " + q;
        noise.measured_shared = true;  // from the whole image: its own dof is large, taken as ∞
    }
    return std::vector<float>(measured.pixel_count(), static_cast<float>(sigma * sigma));
}

using VarianceByQuantity = StokesValues<std::vector<float>>;

// Per-pixel differences and z = (m − s)/√(σ_m² + σ_s²) for S0, S1, S2, with where each σ came from.
void differences_and_z(Comparison& comparison, const Headers& headers,
                       const CompareOptions& options, VarianceByQuantity& var_measured,
                       VarianceByQuantity& var_simulated) {
    CompareResult& result = comparison.result;
    ComparisonPlanes& planes = comparison.planes;
    const std::size_t n = planes.measured.pixel_count();
    for (const auto& q : std::vector<std::string>{"S0", "S1", "S2", "DoLP", "AoP"})
        planes.difference[q] =
            difference(planes.measured.channel(q), planes.simulated.channel(q), q == "AoP");
    for (const Quantity quantity : kZQuantities) {
        const std::string& q = quantity_name(quantity);
        throw_if_cancelled(options.cancel, "comparison");
        NoiseSource source;
        source.measured_dof = variance_dof(headers.measured);
        auto var_m = variance_channel(planes.measured, q, source.measured);
        if (!var_m)
            var_m = measured_variance_without_channel(comparison, quantity, options, source);
        auto var_s = variance_channel(planes.simulated, q, source.simulated);
        if (!var_s) {
            source.simulated = "none (σ_s = 0)";
            var_s = std::vector<float>(n, 0.0f);
            result.notes.push_back(fmt::format(
                "{} has no {}_var channel: the z statistic of {} ignores Monte-Carlo noise",
                options.simulated_name, q, q));
        }
        source.measured_sigma_median = median_sqrt(*var_m);
        source.simulated_dof = variance_dof(headers.simulated);
        // Per pixel, a shared measured σ counts as exact: its estimation error is common to the
        // pixels.
        const double measured_pixel_dof =
            source.measured_shared ? kInfiniteDof : source.measured_dof;
        // What a per-pixel value (z, the σ medians, the σ scale of the figures) uses: each pixel's
        // own simulated variance, or below kPerPixelVarianceDof its mean over the pixel's
        // neighbourhood on the same surface (pooled_variance.h; one pixel's estimate alone is
        // too noisy to divide by, and the median of χ²₁ is 0.45 of its mean). The region tests
        // keep the per-pixel channel: their sum over a region is already the pooled estimate.
        std::optional<PooledVariance> pooled;
        if (source.simulated_dof < kPerPixelVarianceDof) {
            std::vector<const std::vector<float>*> labels;
            for (const char* label : {"object_id", "material_id"})
                if (planes.simulated.has_channel(label))
                    labels.push_back(&planes.simulated.channel(label));
            pooled =
                pool_variance(*var_s, labels, planes.simulated.width(), planes.simulated.height(),
                              kVariancePoolRadiusPx, source.simulated_dof);
            source.simulated += fmt::format(
                " ({:g} dof per pixel: per-pixel values use its mean over each pixel's {}×{} "
                "neighbourhood on the same surface)",
                source.simulated_dof, 2 * kVariancePoolRadiusPx + 1, 2 * kVariancePoolRadiusPx + 1);
        }
        const std::vector<float>& shown_var_s = pooled ? pooled->variance : *var_s;
        source.simulated_sigma_median = median_sqrt(shown_var_s);
        planes.z[q] = pooled ? z_scores(planes.measured.channel(q), planes.simulated.channel(q),
                                        *var_m, pooled->variance, measured_pixel_dof, pooled->dof)
                             : z_scores(planes.measured.channel(q), planes.simulated.channel(q),
                                        *var_m, *var_s, measured_pixel_dof, source.simulated_dof);
        result.noise[quantity] = source;
        std::vector<float> total(n);
        for (std::size_t i = 0; i < n; ++i) total[i] = (*var_m)[i] + shown_var_s[i];
        planes.total_variance[q] = std::move(total);
        var_measured[quantity] = std::move(*var_m);
        var_simulated[quantity] = std::move(*var_s);
    }
}

// Mean gradient (per pixel, x and y) of `plane` over the masked pixels whose central differences
// are finite.
std::array<double, 2> mean_gradient(const std::vector<float>& plane, int width, int height,
                                    const Mask& mask) {
    double gx = 0.0, gy = 0.0;
    std::size_t nx = 0, ny = 0;
    const auto at = [&](int x, int y) {
        return plane[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                     static_cast<std::size_t>(x)];
    };
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            if (!mask[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                      static_cast<std::size_t>(x)])
                continue;
            if (x > 0 && x + 1 < width && std::isfinite(at(x + 1, y)) &&
                std::isfinite(at(x - 1, y))) {
                gx += 0.5 * (static_cast<double>(at(x + 1, y)) - at(x - 1, y));
                ++nx;
            }
            if (y > 0 && y + 1 < height && std::isfinite(at(x, y + 1)) &&
                std::isfinite(at(x, y - 1))) {
                gy += 0.5 * (static_cast<double>(at(x, y + 1)) - at(x, y - 1));
                ++ny;
            }
        }
    return {nx ? gx / static_cast<double>(nx) : 0.0, ny ? gy / static_cast<double>(ny) : 0.0};
}

// The region-mean test and σ diagnostic of quantity `q` in region `r`. Common to the region's
// pixels: the calibration's gain (all of S0..S2) and offset (S0; it cancels in S1 = I0 − I90, S2 =
// I45 − I135) and the residual misalignment, which moves the region over the simulation's mean
// gradient.
QuantityVerdict quantity_verdict(const ComparisonPlanes& planes, const CompareResult& result,
                                 const CompareOptions& options, std::size_t r, Quantity quantity,
                                 const VarianceByQuantity& var_measured,
                                 const VarianceByQuantity& var_simulated,
                                 const QuantityStats& stats) {
    const std::string& q = quantity_name(quantity);
    const Mask& mask = planes.masks[r];
    const NoiseSource& noise = result.noise[quantity];
    MeanDifferenceInputs in;
    in.measured = &planes.measured.channel(q);
    in.simulated = &planes.simulated.channel(q);
    in.measured_variance = &var_measured[quantity];
    in.simulated_variance = &var_simulated[quantity];
    in.mask = &mask;
    in.measured_dof = noise.measured_dof;
    in.simulated_dof = noise.simulated_dof;
    in.measured_variance_shared = noise.measured_shared;
    const double gain = options.measured_gain_sigma_relative * std::abs(stats.measured_mean);
    const double offset = quantity == Quantity::S0 ? options.measured_offset_sigma : 0.0;
    in.measured_common.sigma = std::hypot(gain, offset);
    const auto g = mean_gradient(*in.simulated, result.width, result.height, mask);
    in.registration.sigma = std::abs(result.registration.residual_shift_px[0] * g[0] +
                                     result.registration.residual_shift_px[1] * g[1]);
    return {test_mean_difference(in, options.design), sigma_diagnostic(planes.z.at(q), mask)};
}

// Statistics, z summary, verdicts, AoP and kelvin bias of region `r`.
RegionResult region_result(const ComparisonPlanes& planes, const CompareResult& result,
                           const CompareOptions& options, std::size_t r,
                           const std::vector<float>& z_pooled,
                           const VarianceByQuantity& var_measured,
                           const VarianceByQuantity& var_simulated,
                           const std::optional<Band>& band) {
    const Image& measured = planes.measured;
    const Image& simulated = planes.simulated;
    const Mask& mask = planes.masks[r];
    RegionResult rr;
    rr.name = planes.regions[r].name;
    rr.pixel_count = static_cast<std::size_t>(std::count(mask.begin(), mask.end(), 1));
    for (const Quantity q : kComparedQuantities)
        rr.stats[q] = quantity_stats(measured.channel(quantity_name(q)),
                                     simulated.channel(quantity_name(q)), mask);
    Mask pooled_mask;
    for (const Quantity q : kZQuantities) {
        rr.z[q] = z_stats(planes.z.at(quantity_name(q)), mask);
        pooled_mask.insert(pooled_mask.end(), mask.begin(), mask.end());
    }
    rr.z_pooled = z_stats(z_pooled, pooled_mask);
    for (const Quantity q : kZQuantities) {
        rr.verdicts[q] = quantity_verdict(planes, result, options, r, q, var_measured,
                                          var_simulated, rr.stats[q]);
        rr.verdict = worse(rr.verdict, rr.verdicts[q].mean.verdict);
    }
    rr.aop = aop_stats(
        {measured.channel("S1"), measured.channel("S2"), var_measured.s1, var_measured.s2},
        {simulated.channel("S1"), simulated.channel("S2"), var_simulated.s1, var_simulated.s2},
        mask);
    if (band) rr.s0_bias_k = kelvin_bias(rr.stats.s0, *band);
    return rr;
}

// S1 contrast of each region against the background region, when there is one.
void background_contrast(CompareResult& result, const std::vector<Region>& regions) {
    const std::size_t bg =
        result.background.empty() ? regions.size() : region_index(regions, result.background);
    if (bg >= regions.size()) return;
    const auto& b = result.regions[bg].stats.s1;
    for (auto& rr : result.regions) {
        const auto& s = rr.stats.s1;
        if (s.pixel_count == 0 || b.pixel_count == 0) continue;
        rr.s1_contrast_measured = s.measured_mean - b.measured_mean;
        rr.s1_contrast_simulated = s.simulated_mean - b.simulated_mean;
    }
}

// z of S0, S1 and S2 end to end (the pooled sample of the histogram and the "all" statistic).
std::vector<float> pooled_z(const ComparisonPlanes& planes) {
    std::vector<float> z_pooled;
    for (const Quantity q : kZQuantities) {
        const auto& z = planes.z.at(quantity_name(q));
        z_pooled.insert(z_pooled.end(), z.begin(), z.end());
    }
    return z_pooled;
}

// The files of a report being written, and the figures its page will show, in order.
struct ReportFiles {
    CompareResult& result;
    const ComparisonPlanes& planes;
    std::filesystem::path dir;
    std::vector<detail::Figure> figures;

    std::filesystem::path png(const std::string& name) {
        result.pngs.push_back(dir / name);
        return dir / name;
    }
    // A plot: written next to the page as .svg and inlined in it.
    void svg_figure(const std::string& section, const std::string& name, std::string svg,
                    std::string caption) {
        result.svgs.push_back(dir / name);
        write_file_atomic(dir / name, "<svg xmlns=\"http://www.w3.org/2000/svg\" " + svg.substr(5));
        figures.push_back({section, dir / name, std::move(caption), std::move(svg)});
    }
};

QuantityDisplay display_of(const std::string& q, const std::string& units) {
    if (q == "DoLP") return {"", Colormap::Sequential};
    if (q == "AoP") return {"°", Colormap::Cyclic};
    return {units, q == "S0" ? Colormap::Sequential : Colormap::Diverging};
}

void regions_figure(ReportFiles& f) {
    const auto& r = f.result;
    f.svg_figure(
        "regions", "regions.svg",
        detail::svg_region_overview(detail::region_overview(f.planes.measured.channel("S0"),
                                                            r.width, r.height, f.planes.regions)),
        "Measured S0 with the regions of interest (polygons in measured pixel coordinates).");
}

// Measured, simulated and their difference of quantity `q`, the first two on one colour scale.
void image_panel(ReportFiles& f, const std::string& q) {
    const int w = f.result.width, h = f.result.height;
    const QuantityDisplay d = display_of(q, f.result.units);
    const auto pm = detail::display_plane(f.planes.measured.channel(q), w, h);
    const auto ps = detail::display_plane(f.planes.simulated.channel(q), w, h);
    const auto pd = detail::display_plane(f.planes.difference.at(q), w, h);
    QuicklookOptions shared{d.map, std::nullopt, std::nullopt, "", d.units, 0};
    if (q == "DoLP") shared.vmin = 0.0;
    const auto [lo, hi] = shared_range(pm.data, ps.data, shared);
    shared.vmin = lo;
    shared.vmax = hi;
    QuicklookOptions om = shared, os = shared,
                     od{Colormap::Diverging,         std::nullopt, std::nullopt,
                        q + " measured - simulated", d.units,      0};
    om.title = q + " measured";
    os.title = q + " simulated";
    if (q == "AoP") {
        od.vmin = -90.0;
        od.vmax = 90.0;
    }
    const auto [dlo, dhi] = quicklook_range(pd.data, od);
    od.vmin = dlo;
    od.vmax = dhi;
    f.result.colour_scales[q] = {lo, hi};
    f.result.colour_scales[q + "_difference"] = {dlo, dhi};
    detail::write_panel(f.png("panel_" + q + ".png"),
                        {f.png("measured_" + q + ".png"), f.png("simulated_" + q + ".png"),
                         f.png("difference_" + q + ".png")},
                        {pm, ps, pd}, {om, os, od});
    const std::string unit_text = d.units.empty() ? "" : " " + d.units;
    f.figures.push_back(
        {"images", f.dir / ("panel_" + q + ".png"),
         fmt::format("{}: measured (left) and registered simulation (centre) on one colour scale "
                     "{:.4g} to {:.4g}{}; right: measured − simulated, {:.4g} to {:.4g}{}{}.",
                     q, lo, hi, unit_text, dlo, dhi, unit_text,
                     q == "AoP" ? " (wrapped to ±90°; meaningless where DoLP ≈ 0)" : ""),
         ""});
}

void image_panels(ReportFiles& f) {
    for (const auto& q : std::vector<std::string>{"S0", "S1", "S2", "DoLP", "AoP"})
        image_panel(f, q);
}

void z_figures(ReportFiles& f) {
    std::vector<detail::Plane> z_planes;
    std::vector<std::filesystem::path> parts;
    std::vector<QuicklookOptions> opts;
    for (const Quantity quantity : kZQuantities) {
        const std::string& q = quantity_name(quantity);
        z_planes.push_back(
            detail::display_plane(f.planes.z.at(q), f.result.width, f.result.height));
        parts.push_back(f.png("z_" + q + ".png"));
        opts.push_back({Colormap::Diverging, -5.0, 5.0, "z " + q, "sigma", 0});
    }
    f.result.colour_scales["z"] = {-5.0, 5.0};
    detail::write_panel(f.png("panel_z.png"), parts, z_planes, opts);
    f.figures.push_back(
        {"z", f.dir / "panel_z.png",
         "z = (measured − simulated)/√(σ_m² + σ_s²) for S0, S1 and S2, colour scale −5 to 5. "
         "Where the simulation is right, z is standard normal: |z| > 2 in 4.55 % of pixels.",
         ""});
    f.svg_figure("z", "histogram_z.svg",
                 detail::svg_histogram("z of S0, S1, S2 (all pixels)", "z", pooled_z(f.planes),
                                       -6.0, 6.0, {-3, -2, 0, 2, 3}, 0.0, 1.0),
                 "Distribution of z over all pixels (bars) against the standard normal density "
                 "(red curve); grey "
                 "lines at ±2 and ±3.");
}

void scatter_figures(ReportFiles& f) {
    const auto& regions = f.planes.regions;
    const auto& masks = f.planes.masks;
    for (const Quantity quantity : kComparedQuantities) {
        const std::string& q = quantity_name(quantity);
        std::vector<detail::ScatterSeries> series;
        const auto& mq = f.planes.measured.channel(q);
        const auto& sq = f.planes.simulated.channel(q);
        for (std::size_t r = 0; r < regions.size(); ++r) {
            detail::ScatterSeries s{regions[r].name, {}, {}};
            for (std::size_t i = 0; i < mq.size(); ++i)
                if (masks[r][i]) {
                    s.measured.push_back(mq[i]);
                    s.simulated.push_back(sq[i]);
                }
            series.push_back(std::move(s));
        }
        f.svg_figure(
            "scatter", "scatter_" + q + ".svg",
            detail::svg_scatter(q, display_of(q, f.result.units).units, series),
            fmt::format(
                "{}: simulated against measured per pixel, one colour per region; dashed: 1:1.",
                q));
    }
}

// Histogram of measured − simulated of `q` against the normal density of the stated noise.
void difference_histogram(ReportFiles& f, const std::string& q) {
    const auto& d = f.planes.difference.at(q);
    std::vector<float> finite_abs;
    double bias = 0.0;
    for (float v : d)
        if (std::isfinite(v)) {
            finite_abs.push_back(std::abs(v));
            bias += v;
        }
    bias = finite_abs.empty() ? 0.0 : bias / static_cast<double>(finite_abs.size());
    double range = 1.0;
    if (!finite_abs.empty()) {
        const auto k = static_cast<std::size_t>(0.995 * static_cast<double>(finite_abs.size() - 1));
        std::nth_element(finite_abs.begin(), finite_abs.begin() + static_cast<std::ptrdiff_t>(k),
                         finite_abs.end());
        range = finite_abs[k] > 0.0f ? 1.1 * finite_abs[k] : 1.0;
    }
    const auto& total_variance = f.planes.total_variance;
    const double sigma = total_variance.count(q) ? median_sqrt(total_variance.at(q)) : 0.0;
    const std::string units = display_of(q, f.result.units).units;
    f.svg_figure(
        "histograms", "histogram_difference_" + q + ".svg",
        detail::svg_histogram(q + ": measured − simulated",
                              "difference" + (units.empty() ? "" : " [" + units + "]"), d, -range,
                              range, {0.0, bias}, 0.0, sigma),
        sigma > 0.0
            ? fmt::format("{}: measured − simulated over all pixels; red: the normal density "
                          "expected from noise alone (σ = {:.3g}); grey: 0 and the mean {:.3g}.",
                          q, sigma, bias)
            : fmt::format("{}: measured − simulated over all pixels; grey: 0 and the mean {:.3g}.",
                          q, bias));
}

void difference_histograms(ReportFiles& f) {
    for (const Quantity q : kComparedQuantities) difference_histogram(f, quantity_name(q));
}

// Full-resolution planes behind the figures.
void planes_exr(ReportFiles& f) {
    Image exr_planes(f.result.width, f.result.height);
    write_stokes_image_header(exr_planes, {.units = f.result.units});
    for (const auto& q : std::vector<std::string>{"S0", "S1", "S2", "DoLP", "AoP"}) {
        exr_planes.set_channel("measured." + q, f.planes.measured.channel(q));
        exr_planes.set_channel("simulated." + q, f.planes.simulated.channel(q));
        exr_planes.set_channel("difference." + q, f.planes.difference.at(q));
    }
    for (const Quantity quantity : kZQuantities) {
        const std::string& q = quantity_name(quantity);
        exr_planes.set_channel("z." + q, f.planes.z.at(q));
    }
    f.result.exr = f.dir / "comparison.exr";
    write_exr(f.result.exr, exr_planes);
}

// The report, section by section in page order: a new figure is one more entry.
using Section = void (*)(ReportFiles&);
constexpr Section kSections[] = {regions_figure,  image_panels,          z_figures,
                                 scatter_figures, difference_histograms, planes_exr};

}  // namespace

void require_stokes_channels(const Image& image, const std::string& name, const std::string& role) {
    std::vector<std::string> missing;
    for (const char* c : {"S0", "S1", "S2"})
        if (!image.has_channel(c)) missing.emplace_back(c);
    if (!missing.empty())
        fail(
            "{}: the {} Stokes image lacks channel{} {}; channels present: {} (expected S0 S1 S2, "
            "as written by "
            "`tirpol {}`)",
            name, role, missing.size() > 1 ? "s" : "", join(missing), join(image.channel_names()),
            role == "measured" ? "reduce" : "render");
    if (image.pixel_count() == 0) fail("{}: the {} Stokes image has no pixels", name, role);
}

Comparison compare(const Image& measured_in, const Image& simulated_in,
                   const CompareOptions& options) {
    require_stokes_channels(measured_in, options.measured_name, "measured");
    require_stokes_channels(simulated_in, options.simulated_name, "simulated");
    const Headers headers{read_stokes_image_header(measured_in, options.measured_name),
                          read_stokes_image_header(simulated_in, options.simulated_name)};
    Comparison comparison = start_comparison(measured_in, simulated_in, headers.measured, options);
    comparison.result.design = options.design;
    comparison.result.calibration_range = calibration_range(headers.measured);
    describe_sigma_contents(comparison.result, headers, options);
    register_planes(comparison, measured_in, simulated_in, options);
    VarianceByQuantity var_measured, var_simulated;
    differences_and_z(comparison, headers, options, var_measured, var_simulated);
    const std::vector<float> z_pooled = pooled_z(comparison.planes);
    const std::optional<Band> band = comparison_band(headers, options, comparison.result);
    for (std::size_t r = 0; r < comparison.planes.regions.size(); ++r) {
        throw_if_cancelled(options.cancel, "comparison");
        comparison.result.regions.push_back(region_result(comparison.planes, comparison.result,
                                                          options, r, z_pooled, var_measured,
                                                          var_simulated, band));
    }
    background_contrast(comparison.result, comparison.planes.regions);
    return comparison;
}

void write_report(Comparison& comparison, const CompareOptions& options,
                  const std::filesystem::path& report_dir) {
    std::filesystem::create_directories(report_dir);
    ReportFiles files{comparison.result, comparison.planes, report_dir, {}};
    for (const Section section : kSections) section(files);
    CompareResult& result = comparison.result;
    // Input files are named relative to the report's folder, so that the folder moves with its
    // inputs (and no home directory is published).
    for (auto& input : result.provenance.inputs)
        input.path = path_relative_to(input.path, report_dir);
    const auto shown_name = [&](const std::string& name) {
        std::error_code error;
        return std::filesystem::is_regular_file(name, error)
                   ? path_relative_to(name, report_dir).string()
                   : name;
    };
    result.json = report_dir / "report.json";
    result.html = report_dir / "report.html";
    write_file_atomic(result.json, comparison_json(result));
    write_file_atomic(result.html,
                      detail::render_html(result, shown_name(options.measured_name),
                                          shown_name(options.simulated_name), files.figures));
}

CompareResult write_comparison_report(const Image& measured, const Image& simulated,
                                      const CompareOptions& options,
                                      const std::filesystem::path& report_dir) {
    Comparison comparison = compare(measured, simulated, options);
    write_report(comparison, options, report_dir);
    return std::move(comparison.result);
}

}  // namespace tirpol::report
