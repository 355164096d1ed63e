#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "tirpol/core/error.h"
#include "tirpol/sweep/sweep_run.h"

namespace tirpol::sweep {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Mean of `values` under `mask` and its standard error √(Σ var_i)/n; pixels with a non-finite
/// value are left out. `variances` may be empty (an exact quantity: error 0).
Estimate masked_estimate(const std::vector<float>& values, const std::vector<double>& variances,
                         const std::vector<std::uint8_t>& mask) {
    double sum = 0.0, variance_sum = 0.0;
    std::size_t n = 0;
    for (std::size_t i = 0; i < values.size(); ++i) {
        if (!mask[i] || !std::isfinite(values[i])) continue;
        sum += values[i];
        if (!variances.empty()) variance_sum += variances[i];
        ++n;
    }
    if (n == 0) return {kNaN, kNaN};
    const double count = static_cast<double>(n);
    return {sum / count, std::sqrt(variance_sum) / count};
}

std::vector<double> as_double(const std::vector<float>& v) { return {v.begin(), v.end()}; }

/// First-order variance of each pixel's DoLP = √(S1² + S2²)/S0 from the variances of S0, S1, S2.
std::vector<double> dolp_variance(const Image& image) {
    const auto &s0 = image.channel("S0"), &s1 = image.channel("S1"), &s2 = image.channel("S2");
    const auto &v0 = image.channel("S0_var"), &v1 = image.channel("S1_var"),
               &v2 = image.channel("S2_var");
    std::vector<double> out(s0.size(), 0.0);
    for (std::size_t i = 0; i < s0.size(); ++i) {
        const double p2 = double(s1[i]) * s1[i] + double(s2[i]) * s2[i];
        const double i0 = s0[i];
        if (p2 <= 0.0 || i0 <= 0.0) continue;
        out[i] = (s1[i] * s1[i] * double(v1[i]) + s2[i] * s2[i] * double(v2[i])) / (p2 * i0 * i0) +
                 p2 * v0[i] / (i0 * i0 * i0 * i0);
    }
    return out;
}

Estimate difference(const Estimate& a, const Estimate& b) {
    return {a.mean - b.mean, std::hypot(a.error, b.error)};
}

}  // namespace

const Estimate& quantity(const QuantityEstimates& q, std::size_t index) {
    const Estimate* all[] = {&q.s0, &q.s1, &q.s2, &q.dolp, &q.temperature_k};
    return *all[index];
}

std::vector<std::uint8_t> region_pixels(const Image& image, const std::vector<std::string>& objects,
                                        const RegionSpec& region) {
    const int w = image.width(), h = image.height();
    std::vector<std::uint8_t> mask(image.pixel_count(), 1);
    if (region.polygon) mask = report::region_mask(*region.polygon, w, h);
    if (region.object.empty()) return mask;
    const auto it = std::find(objects.begin(), objects.end(), region.object);
    if (it == objects.end())
        fail("{}: region '{}': the scene has no object '{}'", region.location, region.name,
             region.object);
    const float id = static_cast<float>(it - objects.begin());
    const auto& object_id = image.channel("object_id");
    double cx = 0.0, cy = 0.0, n = 0.0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (object_id[image.index(x, y)] == id) cx += x, cy += y, n += 1.0;
    cx /= std::max(n, 1.0);
    cy /= std::max(n, 1.0);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            std::uint8_t& m = mask[image.index(x, y)];
            m = m && object_id[image.index(x, y)] == id;
            if (!m || region.sectors_deg.empty()) continue;
            // Image rows grow downward; 90° is the top of the image, as the Stokes reference
            // (conventions.md).
            const double angle_deg = std::atan2(cy - y, x - cx) * 180.0 / std::numbers::pi;
            bool inside = false;
            for (const auto& [from, to] : region.sectors_deg) {
                const double a =
                    from + std::fmod(std::fmod(angle_deg - from, 360.0) + 360.0, 360.0);
                inside = inside || a <= to;
            }
            m = inside;
        }
    }
    return mask;
}

PointStatistics point_statistics(const Image& image, const std::vector<std::string>& objects,
                                 const SweepSpec& spec) {
    const auto v0 = as_double(image.channel("S0_var")), v1 = as_double(image.channel("S1_var")),
               v2 = as_double(image.channel("S2_var")), vd = dolp_variance(image);
    PointStatistics out;
    for (const RegionSpec& region : spec.regions) {
        const auto mask = region_pixels(image, objects, region);
        RegionStatistics r{region.name, 0, {}};
        for (auto m : mask) r.pixel_count += m;
        r.values = {masked_estimate(image.channel("S0"), v0, mask),
                    masked_estimate(image.channel("S1"), v1, mask),
                    masked_estimate(image.channel("S2"), v2, mask),
                    masked_estimate(image.channel("DoLP"), vd, mask),
                    masked_estimate(image.channel("temperature_k"), {}, mask)};
        out.regions.push_back(std::move(r));
    }
    const auto find = [&](const std::string& name) -> const QuantityEstimates& {
        for (const auto& r : out.regions)
            if (r.name == name) return r.values;
        fail("contrast names an unknown region '{}'", name);
    };
    for (const ContrastSpec& c : spec.contrasts) {
        const QuantityEstimates &a = find(c.a), &b = find(c.b);
        out.contrasts.push_back(
            {c.name,
             {difference(a.s0, b.s0), difference(a.s1, b.s1), difference(a.s2, b.s2),
              difference(a.dolp, b.dolp), difference(a.temperature_k, b.temperature_k)}});
    }
    return out;
}

}  // namespace tirpol::sweep
