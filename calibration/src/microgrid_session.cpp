#include "tirpol/calibration/microgrid_session.h"

#include <cmath>

#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/session.h"

namespace tirpol::calibration {

namespace {
// The session reduction's own attributes (the Stokes EXR's names), written and read only here.
constexpr const char* kRecordsAveraged = "records_averaged";
constexpr const char* kFramesAveraged = "frames_averaged";
}  // namespace

bool is_microgrid_session(const std::filesystem::path& dir) {
    return read_session(dir).camera.microgrid_pattern_deg.has_value();
}

Image reduce_microgrid_session(const std::filesystem::path& dir,
                               const MicrogridSessionOptions& options) {
    const SessionManifest manifest = read_session(dir);
    const std::string manifest_path = (dir / kSessionManifestName).string();
    if (!manifest.camera.microgrid_pattern_deg)
        fail(
            "{}: camera.microgrid_pattern_deg is null: a session of a camera without a microgrid "
            "(reduce it with a radiometric calibration, --calibration)",
            manifest_path);
    const MicrogridPattern pattern(*manifest.camera.microgrid_pattern_deg,
                                   manifest_path + ": camera.microgrid_pattern_deg");
    const int width = manifest.camera.width, height = manifest.camera.height;
    // The frames' mean over every polarizer record, weighted by frames: each record is already the
    // mean of its frames, and a microgrid frame needs no polarizer angle.
    std::vector<double> sum(static_cast<std::size_t>(width) * static_cast<std::size_t>(height),
                            0.0);
    // Its variance from the records' temporal σ: a record's mean of n_r frames of σ_r weighs
    // n_r/N, so Var = Σ_r n_r·σ_r²/N². Known only when every record averaged ≥ 2 frames.
    std::vector<double> variance_sum(sum.size(), 0.0);
    bool temporal_noise_known = true;
    std::int64_t frames = 0, records = 0;
    for (const SessionRecord& record : manifest.records) {
        if (record.kind != RecordKind::Polarizer) continue;
        const Image frame = read_session_frame(dir, manifest, record);
        const std::vector<float>& counts = frame.channel("counts");
        const std::vector<float>& counts_std = frame.channel("counts_std");
        const auto n_frames = static_cast<double>(record.frames);
        for (std::size_t i = 0; i < sum.size(); ++i) {
            sum[i] += static_cast<double>(counts[i]) * n_frames;
            variance_sum[i] +=
                n_frames * static_cast<double>(counts_std[i]) * static_cast<double>(counts_std[i]);
        }
        temporal_noise_known = temporal_noise_known && record.frames > 1;
        frames += record.frames;
        ++records;
    }
    if (records == 0)
        fail("{}: no polarizer record to reduce (expected at least one record of kind polarizer)",
             manifest_path);
    std::vector<float> mean(sum.size());
    for (std::size_t i = 0; i < sum.size(); ++i)
        mean[i] = static_cast<float>(sum[i] / static_cast<double>(frames));

    Image stokes;
    if (options.pixel_calibration) {
        const MicrogridPixelCalibration& c = *options.pixel_calibration;
        if (c.width != width || c.height != height)
            fail(
                "per-pixel calibration is {}×{}, the session's camera {}×{} ({}); expected a "
                "calibration of this camera",
                c.width, c.height, width, height, manifest_path);
        std::vector<float> mean_std;
        if (temporal_noise_known) {
            mean_std.resize(sum.size());
            const double n_squared = static_cast<double>(frames) * static_cast<double>(frames);
            for (std::size_t i = 0; i < sum.size(); ++i)
                mean_std[i] = static_cast<float>(std::sqrt(variance_sum[i] / n_squared));
        }
        stokes = MicrogridPixelReducer(c).reduce(mean, mean_std);
        pattern.write_to(stokes.attributes());
    } else {
        MicrogridReductionOptions reduction;
        reduction.method = options.method;
        reduction.reduction.units = "counts";
        reduction.source = dir.string();
        stokes = reduce_microgrid(mean, width, height, pattern, reduction);
    }
    stokes.attributes()["session"] = dir.string();
    stokes.attributes()[kRecordsAveraged] = static_cast<int>(records);
    stokes.attributes()[kFramesAveraged] = static_cast<int>(frames);
    return stokes;
}

MicrogridSessionRecord microgrid_session_record(const Image& stokes) {
    const auto integer = [&](const char* name) {
        const auto it = stokes.attributes().find(name);
        if (it == stokes.attributes().end())
            fail("Stokes image: no attribute '{}' (not reduced from a microgrid session?)", name);
        if (!std::holds_alternative<int>(it->second))
            fail("Stokes image: attribute '{}' is not an integer", name);
        return std::get<int>(it->second);
    };
    // Written by the ideal reduction ("counts") and by a per-pixel calibration that knows its
    // Stokes units; absent otherwise.
    std::string units = read_stokes_image_header(stokes, "Stokes image").units.value_or("");
    return {MicrogridPattern::from_attributes(stokes.attributes()), integer(kRecordsAveraged),
            integer(kFramesAveraged), std::move(units)};
}

}  // namespace tirpol::calibration
