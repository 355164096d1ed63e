#include "tirpol/calibration/microgrid_session.h"

#include "tirpol/core/error.h"
#include "tirpol/core/session.h"

namespace tirpol::calibration {

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
    std::int64_t frames = 0, records = 0;
    for (const SessionRecord& record : manifest.records) {
        if (record.kind != RecordKind::Polarizer) continue;
        const Image frame = read_session_frame(dir, manifest, record);
        const std::vector<float>& counts = frame.channel("counts");
        for (std::size_t i = 0; i < sum.size(); ++i)
            sum[i] += static_cast<double>(counts[i]) * static_cast<double>(record.frames);
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
        stokes = reduce_microgrid_per_pixel(mean, c);
        pattern.write_to(stokes.attributes());
    } else {
        MicrogridReductionOptions reduction;
        reduction.method = options.method;
        reduction.reduction.units = "counts";
        reduction.source = dir.string();
        stokes = reduce_microgrid(mean, width, height, pattern, reduction);
    }
    stokes.attributes()["session"] = dir.string();
    stokes.attributes()["records_averaged"] = static_cast<int>(records);
    stokes.attributes()["frames_averaged"] = static_cast<int>(frames);
    return stokes;
}

}  // namespace tirpol::calibration
