#include "offset_drift.h"

#include <algorithm>
#include <cmath>

#include "tirpol/core/error.h"
#include "validate.h"

namespace tirpol::calibration {

namespace fs = std::filesystem;

namespace {
std::string manifest_path(const fs::path& dir) { return (dir / kSessionManifestName).string(); }

double record_time_s(const SessionRecord& r) {
    return 0.5e-9 *
           (static_cast<double>(r.first_timestamp_ns) + static_cast<double>(r.last_timestamp_ns));
}

double number(const nlohmann::json& node, const char* key, const std::string& where, double lo,
              double hi) {
    if (!node.contains(key) || !node[key].is_number() ||
        !(node[key].get<double>() >= lo && node[key].get<double>() <= hi))
        fail("{}.{}: expected a number in [{}, {}]", where, key, lo, hi);
    return node[key].get<double>();
}

std::vector<std::size_t> roi_pixels(const SceneReferenceRegion& roi, int image_width) {
    std::vector<std::size_t> out;
    for (int y = roi.y; y < roi.y + roi.height; ++y)
        for (int x = roi.x; x < roi.x + roi.width; ++x)
            out.push_back(static_cast<std::size_t>(y) * static_cast<std::size_t>(image_width) +
                          static_cast<std::size_t>(x));
    return out;
}

/// The shift in one record: its frame against the expected radiance over `pixels`.
OffsetDriftPoint measure_record(const fs::path& dir, const SessionManifest& m,
                                const SessionRecord& r, const RadiometricCalibration& calibration,
                                const std::vector<std::size_t>& pixels, double temperature_k,
                                double temperature_sigma_k, double radiance_factor) {
    const std::string src = (dir / r.file).string();
    const RadiometricCalibration cal = at_fpa_temperature(calibration, r.fpa_temperature_k, src);
    const Image frame = read_session_frame(dir, m, r);
    const Band band = cal.band();
    const double l = radiance_factor * band.radiance(temperature_k);
    const double l_sigma = radiance_factor * band.radiance_dT(temperature_k) * temperature_sigma_k;
    return measure_offset_drift(cal, frame.channel("counts"), frame.channel("counts_std"), r.frames,
                                pixels, l, l_sigma, record_time_s(r), src);
}
}  // namespace

std::optional<SceneReferenceRegion> scene_reference_region(const fs::path& dir,
                                                           const SessionManifest& m) {
    const auto it = m.plan.find("scene_reference");
    if (it == m.plan.end()) return std::nullopt;
    const std::string where = manifest_path(dir) + ": plan.scene_reference";
    if (!it->is_object() || !it->contains("roi") || !(*it)["roi"].is_object())
        fail("{}: expected {{roi: {{x, y, width, height}}, temperature_k, temperature_sigma_k}}",
             where);
    const auto& roi = (*it)["roi"];
    SceneReferenceRegion out;
    out.x = static_cast<int>(number(roi, "x", where + ".roi", 0, m.camera.width - 1));
    out.y = static_cast<int>(number(roi, "y", where + ".roi", 0, m.camera.height - 1));
    out.width = static_cast<int>(number(roi, "width", where + ".roi", 1, m.camera.width - out.x));
    out.height =
        static_cast<int>(number(roi, "height", where + ".roi", 1, m.camera.height - out.y));
    out.temperature_k = number(*it, "temperature_k", where, 1.0, 2000.0);
    if (it->contains("temperature_sigma_k"))
        out.temperature_sigma_k = number(*it, "temperature_sigma_k", where, 0.0, 50.0);
    return out;
}

OffsetDriftPoint interpolate_offset_drift(const std::vector<OffsetDriftPoint>& points,
                                          double time_s) {
    if (points.empty()) fail("offset drift: no reference point to interpolate");
    if (time_s <= points.front().time_s)
        return {time_s, points.front().shift_counts, points.front().sigma_counts};
    if (time_s >= points.back().time_s)
        return {time_s, points.back().shift_counts, points.back().sigma_counts};
    const auto after =
        std::upper_bound(points.begin(), points.end(), time_s,
                         [](double t, const OffsetDriftPoint& p) { return t < p.time_s; });
    const OffsetDriftPoint& a = *(after - 1);
    const OffsetDriftPoint& b = *after;
    const double w = (time_s - a.time_s) / (b.time_s - a.time_s);
    return {time_s, (1.0 - w) * a.shift_counts + w * b.shift_counts,
            std::hypot((1.0 - w) * a.sigma_counts, w * b.sigma_counts)};
}

OffsetDriftPoint measure_offset_drift(const RadiometricCalibration& cal,
                                      const std::vector<float>& counts,
                                      const std::vector<float>& counts_std, std::int64_t frames,
                                      const std::vector<std::size_t>& pixels,
                                      double expected_radiance, double radiance_sigma,
                                      double time_s, const std::string& what) {
    detail::check_plane(counts, cal.gain.size(), what + " (counts)", cal.width, cal.height);
    detail::check_plane(counts_std, cal.gain.size(), what + " (counts_std)", cal.width, cal.height);
    double sum = 0.0, var = 0.0, slope = 0.0;
    std::size_t n = 0;
    for (std::size_t i : pixels) {
        if (cal.bad[i] != 0.0f) continue;
        const double q = cal.quadratic.empty() ? 0.0 : cal.quadratic[i];
        const double model = cal.offset[i] + cal.gain[i] * expected_radiance +
                             q * expected_radiance * expected_radiance;
        sum += counts[i] - model;
        var += static_cast<double>(counts_std[i]) * counts_std[i] /
               static_cast<double>(std::max<std::int64_t>(1, frames));
        slope += cal.gain[i] + 2.0 * q * expected_radiance;
        ++n;
    }
    if (n == 0) fail("{}: no good pixel in the offset-drift reference region", what);
    const double nd = static_cast<double>(n);
    // Pixel noise averages down over the region; the reference's temperature error does not.
    const double sigma = std::hypot(std::sqrt(var) / nd, slope / nd * radiance_sigma);
    return {time_s, sum / nd, sigma};
}

SessionOffsetDrift session_offset_drift(const fs::path& dir, const SessionManifest& m,
                                        const RadiometricCalibration& cal) {
    SessionOffsetDrift out;
    if (const auto roi = scene_reference_region(dir, m)) {
        // Seen through the ideal analyzer, an unpolarized source gives half its radiance (row ½·(1,
        // …)).
        const auto pixels = roi_pixels(*roi, m.camera.width);
        out.source =
            fmt::format("scene_reference roi x={} y={} {}x{} at {:.3f} ± {:.3f} K", roi->x, roi->y,
                        roi->width, roi->height, roi->temperature_k, roi->temperature_sigma_k);
        for (const auto& r : m.records)
            if (r.kind == RecordKind::Polarizer) {
                out.files.push_back(r.file);
                out.points.push_back(measure_record(dir, m, r, cal, pixels, roi->temperature_k,
                                                    roi->temperature_sigma_k, 0.5));
            }
        return out;
    }
    std::vector<std::size_t> all(cal.gain.size());
    for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
    std::vector<OffsetDriftPoint> refs;
    for (const auto& r : m.records)
        if (r.kind == RecordKind::Shutter && r.blackbody_temperature_k)
            refs.push_back(
                measure_record(dir, m, r, cal, all, *r.blackbody_temperature_k, 0.0, 1.0));
    if (refs.empty())
        fail(
            "{}: drift correction needs a plan scene_reference (in-scene reference blackbody "
            "region) or shutter "
            "records with a temperature; the session has neither",
            manifest_path(dir));
    std::sort(refs.begin(), refs.end(),
              [](const auto& a, const auto& b) { return a.time_s < b.time_s; });
    out.source = fmt::format("shutter records ({}), interpolated in time", refs.size());
    for (const auto& r : m.records)
        if (r.kind == RecordKind::Polarizer) {
            out.files.push_back(r.file);
            out.points.push_back(interpolate_offset_drift(refs, record_time_s(r)));
        }
    return out;
}

}  // namespace tirpol::calibration
