#include "counts_quicklook.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "tirpol/calibration/session_calibration.h"
#include "tirpol/calibration/stokes_reduction.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/interrupt_signals.h"
#include "tirpol/core/session.h"
#include "tirpol/core/stokes.h"

namespace tirpol::calibration {

namespace {

// Repeats whose polarizer records look at a known source (they calibrate the analyzer; not scene).
std::set<int> known_source_repeats(const SessionManifest& m) {
    std::set<int> repeats;
    if (!m.metadata.contains("known_source") || !m.metadata["known_source"].is_array())
        return repeats;
    for (const auto& e : m.metadata["known_source"])
        if (e.is_object() && e.contains("repeat") && e["repeat"].is_number_integer())
            repeats.insert(e["repeat"].get<int>());
    return repeats;
}

}  // namespace

Image reduce_session_counts(const std::filesystem::path& dir,
                            const CountsQuicklookOptions& options) {
    const SessionManifest m = read_session(dir);
    const std::set<int> skip = known_source_repeats(m);
    const std::optional<double> saturation = session_saturation_counts(m);
    const std::size_t pixels =
        static_cast<std::size_t>(m.camera.width) * static_cast<std::size_t>(m.camera.height);
    struct Accumulator {
        std::vector<double> sum, var;  // counts; variance of each record's frame mean
        int n = 0;
        double angle_sum_deg = 0.0;  // read-back angles of the repeats
        std::string source;
    };
    std::map<long, Accumulator> by_angle;
    std::vector<std::uint8_t> saturated(pixels, 0);
    for (const auto& r : m.records) {
        if (r.kind != RecordKind::Polarizer || skip.count(r.repeat)) continue;
        throw_if_cancelled(options.cancel, "counts quick look");
        const Image frame = read_session_frame(dir, m, r);
        const auto& counts = frame.channel("counts");
        const auto& counts_std = frame.channel("counts_std");
        std::size_t n_saturated = 0;
        if (saturation)
            for (std::size_t i = 0; i < pixels; ++i)
                if (counts[i] >= *saturation) {
                    saturated[i] = 1;
                    ++n_saturated;
                }
        if (static_cast<double>(n_saturated) >
            options.max_saturated_fraction * static_cast<double>(pixels))
            fail(
                "{}: {} of {} pixels are saturated (counts ≥ {}); expected at most {:.3g}% — "
                "reduce the integration time",
                (dir / r.file).string(), n_saturated, pixels, *saturation,
                100.0 * options.max_saturated_fraction);
        Accumulator& acc = by_angle[polarizer_angle_key(r.angle_deg_requested)];
        if (acc.n == 0) {
            acc.sum.assign(pixels, 0.0);
            acc.var.assign(pixels, 0.0);
            acc.source = (dir / r.file).string();
        }
        const double frames = static_cast<double>(std::max<std::int64_t>(1, r.frames));
        for (std::size_t i = 0; i < pixels; ++i) {
            acc.sum[i] += counts[i];
            acc.var[i] += static_cast<double>(counts_std[i]) * counts_std[i] / frames;
        }
        acc.angle_sum_deg += record_polarizer_angle_deg(m, r);
        ++acc.n;
    }
    if (by_angle.empty())
        fail("{}: no polarizer (scene) records for a counts quick look",
             (dir / kSessionManifestName).string());
    if (by_angle.size() < 3)
        fail("{}: a Stokes quick look needs polarizer records at 3 or more angles, got {}",
             (dir / kSessionManifestName).string(), by_angle.size());
    std::vector<AnalyzerImage> images;
    std::vector<double> angles;
    for (const auto& [key, acc] : by_angle) {
        AnalyzerImage im;
        im.angle_deg = acc.angle_sum_deg / acc.n;
        im.source = acc.source;
        im.signal.reserve(pixels);
        im.signal_std.reserve(pixels);
        for (std::size_t i = 0; i < pixels; ++i) {
            im.signal.push_back(static_cast<float>(acc.sum[i] / acc.n));
            im.signal_std.push_back(static_cast<float>(std::sqrt(acc.var[i]) / acc.n));
        }
        angles.push_back(im.angle_deg);
        images.push_back(std::move(im));
    }
    ReductionOptions reduction;
    reduction.units = "counts";
    reduction.cancel = options.cancel;
    Image out = reduce_stokes(images, m.camera.width, m.camera.height, AnalyzerModel::ideal(angles),
                              nullptr, reduction);
    int n_saturated = 0;
    for (std::size_t i = 0; i < pixels; ++i)
        if (saturated[i]) {
            ++n_saturated;
            for (const auto& name : out.channel_names())
                out.channel(name)[i] = std::numeric_limits<float>::quiet_NaN();
        }
    auto& a = out.attributes();
    a["calibration"] = std::string(kCountsQuicklookLabel);
    a["saturated_pixels"] = n_saturated;
    a["session"] = dir.string();
    a["camera"] = fmt::format("{} {} {}", m.camera.vendor, m.camera.model, m.camera.serial);
    a["analyzer"] = std::string("ideal, at the stage's read-back angles (no calibration)");
    write_stokes_image_header(
        out, {.std_includes = "temporal noise of the counts only (frame scatter / √frames); not "
                              "the offset, gain or polarizer terms a calibration removes"});
    return out;
}

}  // namespace tirpol::calibration
