#include "tirpol/calibration/session_calibration.h"

#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "offset_drift.h"
#include "tirpol/core/error.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/geometry.h"
#include "tirpol/core/interrupt_signals.h"
#include "tirpol/core/stokes.h"
#include "tirpol/core/utc_time.h"
#include "validate.h"

namespace tirpol::calibration {

namespace fs = std::filesystem;

std::optional<double> session_saturation_counts(const SessionManifest& m) {
    const int bits = m.camera.bits_per_pixel;
    if (bits >= 1 && bits <= 23) return std::ldexp(1.0, bits) - 1.0;
    return std::nullopt;
}

namespace {
std::string manifest_path(const fs::path& dir) { return (dir / kSessionManifestName).string(); }

/// Where the polarizer was for a record's frames (record_polarizer_angle_deg: measured from schema
/// v2, requested for v1), as an offset from the requested angle. Refuses a v2 record whose
/// read-backs (around the frames) are further from the request than the plan's angle_tolerance_deg:
/// its frames were not taken at its angle.
double measured_offset_deg(const fs::path& dir, const SessionManifest& m, const SessionRecord& r) {
    const double offset =
        angle_difference_deg(record_polarizer_angle_deg(m, r), r.angle_deg_requested);
    const auto tol = m.plan.find("angle_tolerance_deg");
    if (m.schema_version < 2 || tol == m.plan.end() || !tol->is_number()) return offset;
    std::vector<std::pair<const char*, double>> readings{
        {"angle_deg_measured", r.angle_deg_measured}};
    if (r.timing) {
        readings.emplace_back("timing.angle_deg_before_frames", r.timing->angle_deg_before_frames);
        readings.emplace_back("timing.angle_deg_after_frames", r.timing->angle_deg_after_frames);
    }
    for (const auto& [field, value] : readings)
        if (std::abs(angle_difference_deg(value, r.angle_deg_requested)) > tol->get<double>())
            fail(
                "{}: record {}: {} is {:.4f}° for a requested {:.4f}°, further than the plan's "
                "angle_tolerance_deg ({}°): "
                "its frames were not taken at its angle; re-take this step",
                manifest_path(dir), r.file, field, value, r.angle_deg_requested,
                tol->get<double>());
    return offset;
}

std::optional<bool> polarizer_in_beam(const fs::path& dir, const SessionManifest& m) {
    const auto it = m.metadata.find("polarizer_in_beam");
    if (it == m.metadata.end()) return std::nullopt;
    if (!it->is_boolean())
        fail("{}: metadata.polarizer_in_beam: expected true or false", manifest_path(dir));
    return it->get<bool>();
}

std::string camera_id(const SessionManifest& m) {
    return fmt::format("{} {} {} ({})", m.camera.vendor, m.camera.model, m.camera.serial,
                       m.camera.uri);
}

CalibrationCamera calibration_camera(const SessionManifest& m) {
    return {m.camera.vendor, m.camera.model, m.camera.serial, m.camera.pixel_format,
            m.camera.bits_per_pixel};
}

std::string describe_camera(const std::string& vendor, const std::string& model,
                            const std::string& serial, const std::string& pixel_format, int bits,
                            int width, int height) {
    return fmt::format("{} {} serial '{}', {}×{}, {} ({}-bit)", vendor, model, serial, width,
                       height, pixel_format.empty() ? "pixel format unknown" : pixel_format, bits);
}

BlackbodyFrame to_blackbody_frame(const fs::path& dir, const SessionManifest& m,
                                  const SessionRecord& r) {
    const Image frame = read_session_frame(dir, m, r);
    BlackbodyFrame f;
    f.temperature_k = r.blackbody_temperature_k.value_or(std::numeric_limits<double>::quiet_NaN());
    f.counts = frame.channel("counts");
    f.counts_std = frame.channel("counts_std");
    f.frames = static_cast<int>(r.frames);
    f.source = (dir / r.file).string();
    f.fpa_temperature_k = r.fpa_temperature_k;
    return f;
}

/// The drift correction an offset update applied, and the per-pixel uncertainty it adds.
struct OffsetUpdate {
    std::string source;
    double mean_counts = 0.0;  ///< mean over good pixels of the change of offset
    double sigma_counts =
        0.0;  ///< median per-pixel σ of the reference frame's mean (counts_std/√frames)
    double sigma_mk = 0.0;  ///< the same in mK at the reference temperature
};

OffsetUpdate describe_offset_update(const RadiometricCalibration& before,
                                    const RadiometricCalibration& after,
                                    const BlackbodyFrame& ref) {
    OffsetUpdate u;
    u.source = ref.source;
    double sum = 0.0;
    std::size_t n = 0;
    std::vector<float> sigma, gain;
    for (std::size_t i = 0; i < after.offset.size(); ++i) {
        if (after.bad[i] != 0.0f) continue;
        sum += static_cast<double>(after.offset[i]) - before.offset[i];
        ++n;
        sigma.push_back(
            static_cast<float>(ref.counts_std[i] / std::sqrt(static_cast<double>(ref.frames))));
        gain.push_back(after.gain[i]);
    }
    if (n == 0) return u;
    u.mean_counts = sum / static_cast<double>(n);
    u.sigma_counts = robust_stats(sigma).median;
    u.sigma_mk = 1e3 * u.sigma_counts /
                 (robust_stats(gain).median * after.band().radiance_dT(ref.temperature_k));
    return u;
}

bool is_temperature_reference(const SessionRecord& r) {
    return (r.kind == RecordKind::Blackbody || r.kind == RecordKind::Shutter) &&
           r.blackbody_temperature_k.has_value();
}

/// The known-source state of each calibration repeat, from metadata.known_source.
std::map<int, Eigen::Vector3d> known_sources(const fs::path& dir, const SessionManifest& m,
                                             const Band& band) {
    std::map<int, Eigen::Vector3d> out;
    const auto it = m.metadata.find("known_source");
    if (it == m.metadata.end()) return out;
    const std::string where = manifest_path(dir) + ": metadata.known_source";
    if (!it->is_array())
        fail(
            "{}: expected a list of {{repeat, stokes | blackbody_temperature_k, "
            "reference_polarizer_deg}}",
            where);
    for (std::size_t j = 0; j < it->size(); ++j) {
        const auto& e = (*it)[j];
        const std::string at = fmt::format("{}[{}]", where, j);
        if (!e.is_object() || !e.contains("repeat") || !e["repeat"].is_number_integer())
            fail("{}: expected an object with an integer 'repeat'", at);
        Eigen::Vector3d s;
        if (e.contains("stokes")) {
            const auto& v = e["stokes"];
            if (!v.is_array() || v.size() != 3 || !v[0].is_number() || !v[1].is_number() ||
                !v[2].is_number())
                fail("{}.stokes: expected [S0, S1, S2] in W/(m^2 sr)", at);
            s = {v[0].get<double>(), v[1].get<double>(), v[2].get<double>()};
        } else if (e.contains("blackbody_temperature_k") && e.contains("reference_polarizer_deg") &&
                   e["blackbody_temperature_k"].is_number() &&
                   e["reference_polarizer_deg"].is_number()) {
            const double l = band.radiance(e["blackbody_temperature_k"].get<double>());
            const double two_theta = 2.0 * deg_to_rad(e["reference_polarizer_deg"].get<double>());
            s = {0.5 * l, 0.5 * l * std::cos(two_theta), 0.5 * l * std::sin(two_theta)};
        } else {
            fail(
                "{}: expected 'stokes' or both 'blackbody_temperature_k' and "
                "'reference_polarizer_deg'",
                at);
        }
        out[e["repeat"].get<int>()] = s;
    }
    return out;
}

struct RadianceFrame {
    std::vector<float> radiance, sigma;  // σ of the frame mean
    std::vector<std::uint8_t> saturated;
};

/// `offset_shift_counts`: the record's offset drift (offset_drift.h), added to every pixel's
/// offset.
RadianceFrame to_radiance(const fs::path& dir, const SessionManifest& m, const SessionRecord& r,
                          const RadiometricCalibration& calibration,
                          double offset_shift_counts = 0.0) {
    RadiometricCalibration cal =
        at_fpa_temperature(calibration, r.fpa_temperature_k, (dir / r.file).string());
    for (auto& o : cal.offset) o += static_cast<float>(offset_shift_counts);
    if (m.camera.width != cal.width || m.camera.height != cal.height)
        fail("{}: camera is {}×{} but the radiometric calibration is {}×{}", manifest_path(dir),
             m.camera.width, m.camera.height, cal.width, cal.height);
    const Image frame = read_session_frame(dir, m, r);
    const std::string src = (dir / r.file).string();
    const auto& counts = frame.channel("counts");
    detail::check_plane(counts, cal.gain.size(), src + " (counts)", cal.width, cal.height);
    RadianceFrame out;
    out.radiance = counts_to_radiance(cal, counts);
    const auto& std_counts = frame.channel("counts_std");
    detail::check_plane(std_counts, cal.gain.size(), src + " (counts_std)", cal.width, cal.height);
    out.sigma.resize(counts.size());
    const double root_n = std::sqrt(static_cast<double>(std::max<std::int64_t>(1, r.frames)));
    for (std::size_t i = 0; i < counts.size(); ++i) {
        // dL/dcounts of the fitted model: 1/(g + 2qL).
        const double q = cal.quadratic.empty() ? 0.0 : cal.quadratic[i];
        out.sigma[i] = static_cast<float>(std_counts[i] / root_n /
                                          std::abs(cal.gain[i] + 2.0 * q * out.radiance[i]));
    }
    replace_bad_pixels(out.sigma, cal.bad, cal.width, cal.height);
    out.saturated.assign(counts.size(), 0);
    if (const auto sat = session_saturation_counts(m))
        for (std::size_t i = 0; i < counts.size(); ++i)
            out.saturated[i] = counts[i] >= *sat ? 1 : 0;
    return out;
}
}  // namespace

RadiometricCalibration calibrate_radiometric_session(const fs::path& dir, const Band& band,
                                                     RadiometricOptions options) {
    return calibrate_radiometric_sessions({dir}, band, options);
}

RadiometricCalibration calibrate_radiometric_sessions(const std::vector<fs::path>& dirs,
                                                      const Band& band, RadiometricOptions options,
                                                      CalibrationQuality* quality) {
    if (dirs.empty()) fail("radiometric calibration: no session given");
    std::vector<BlackbodyFrame> frames;
    std::optional<SessionManifest> first;
    for (const auto& dir : dirs) {
        const SessionManifest m = read_session(dir);
        if (polarizer_in_beam(dir, m).value_or(false))
            fail(
                "{}: metadata.polarizer_in_beam is true: these blackbody frames were taken through "
                "the polarizer; use "
                "'tirpol calibrate polarimetric' for them",
                manifest_path(dir));
        // Sessions at several camera temperatures calibrate one camera together, never two.
        if (first && (camera_id(m) != camera_id(*first) || m.camera.width != first->camera.width ||
                      m.camera.height != first->camera.height))
            fail(
                "{}: camera {} ({}×{}) differs from {} ({}×{}) of {}; one calibration is for one "
                "camera",
                manifest_path(dir), camera_id(m), m.camera.width, m.camera.height,
                camera_id(*first), first->camera.width, first->camera.height,
                manifest_path(dirs.front()));
        std::size_t found = 0;
        for (const auto& r : m.records)
            if (is_temperature_reference(r)) {
                frames.push_back(to_blackbody_frame(dir, m, r));
                ++found;
            }
        if (found == 0)
            fail(
                "{}: no blackbody (or temperature-tagged shutter) records; radiometric calibration "
                "needs frames of a "
                "blackbody at ≥ 2 temperatures",
                manifest_path(dir));
        if (!first) first = m;
    }
    if (!options.saturation_counts) options.saturation_counts = session_saturation_counts(*first);
    RadiometricCalibration cal =
        fit_radiometric(frames, first->camera.width, first->camera.height, band, options);
    cal.camera_id = camera_id(*first);
    cal.camera = calibration_camera(*first);
    if (quality) {
        *quality = assess_calibration(cal, frames);
        cal.warnings.insert(cal.warnings.end(), quality->warnings.begin(), quality->warnings.end());
    }
    return cal;
}

void check_same_camera(const RadiometricCalibration& cal, const SessionManifest& m,
                       const fs::path& dir) {
    const CalibrationCamera& c = cal.camera;
    std::vector<std::string> differences;
    if (m.camera.width != cal.width || m.camera.height != cal.height) differences.push_back("size");
    if (c.known()) {
        if (c.serial != m.camera.serial) differences.push_back("serial");
        if (c.model != m.camera.model || c.vendor != m.camera.vendor)
            differences.push_back("model");
        if (c.bits_per_pixel != 0 && m.camera.bits_per_pixel != 0 &&
            c.bits_per_pixel != m.camera.bits_per_pixel)
            differences.push_back("bit depth");
        if (!c.pixel_format.empty() && !m.camera.pixel_format.empty() &&
            c.pixel_format != m.camera.pixel_format)
            differences.push_back("pixel format");
    }
    if (differences.empty()) return;
    fail(
        "{}: the radiometric calibration was made with another camera ({} differ{}): calibration "
        "camera {}; session "
        "camera {}. Per-pixel gains and offsets belong to one detector; use --other-camera (C++: "
        "SessionReductionOptions::force_other_camera) only if you know they apply",
        manifest_path(dir), fmt::join(differences, ", "), differences.size() == 1 ? "s" : "",
        describe_camera(c.vendor, c.model, c.serial, c.pixel_format, c.bits_per_pixel, cal.width,
                        cal.height),
        describe_camera(m.camera.vendor, m.camera.model, m.camera.serial, m.camera.pixel_format,
                        m.camera.bits_per_pixel, m.camera.width, m.camera.height));
}

PolarimetricCalibration calibrate_polarimetric_session(
    const fs::path& dir, const RadiometricCalibration& radiometric,
    const std::optional<DatasheetAnalyzer>& datasheet) {
    const SessionManifest m = read_session(dir);
    check_same_camera(radiometric, m, dir);
    if (!polarizer_in_beam(dir, m).value_or(false))
        fail(
            "{}: metadata.polarizer_in_beam must be true for a polarimetric calibration (blackbody "
            "frames taken "
            "through the polarizer at each angle)",
            manifest_path(dir));
    const Band band = radiometric.band();
    std::vector<PolarizedBlackbodyFrame> bb;
    for (const auto& r : m.records)
        if (r.kind == RecordKind::Blackbody) {
            RadianceFrame f = to_radiance(dir, m, r, radiometric);
            // Grouped by the nominal angle (the fitted analyzer absorbs the mount's offset); the
            // read-back is checked.
            measured_offset_deg(dir, m, r);
            bb.push_back({r.angle_deg_requested, *r.blackbody_temperature_k, std::move(f.radiance),
                          (dir / r.file).string(), std::move(f.sigma)});
        }
    if (bb.empty())
        fail("{}: no blackbody records taken through the polarizer", manifest_path(dir));
    PolarimetricCalibration out;
    out.wire_grid = fit_wire_grid(bb, radiometric.width, radiometric.height, band);
    out.session = dir.string();
    out.created_utc = utc_now_iso8601();
    out.band_lo_um = radiometric.band_lo_um;
    out.band_hi_um = radiometric.band_hi_um;
    std::vector<double> angles;
    for (const auto& p : out.wire_grid.positions) angles.push_back(p.angle_deg);

    // Known-source repeats: the spatial mean of L_SLAR = (L − B)/τ over good pixels, per angle.
    const auto sources = known_sources(dir, m, band);
    if (sources.empty()) {
        out.analyzer =
            datasheet ? datasheet_analyzer_model(angles, *datasheet) : AnalyzerModel::ideal(angles);
        out.analyzer_method = (datasheet ? describe(*datasheet) : std::string("ideal")) +
                              " (no known-source records)";
        return out;
    }
    std::vector<KnownSourceMeasurement> measurements;
    for (const auto& [repeat, stokes] : sources) {
        KnownSourceMeasurement meas{stokes, {}};
        for (const auto& pos : out.wire_grid.positions) {
            const SessionRecord* rec = nullptr;
            for (const auto& r : m.records)
                if (r.kind == RecordKind::Polarizer && r.repeat == repeat &&
                    same_polarizer_angle(r.angle_deg_requested, pos.angle_deg))
                    rec = &r;
            if (rec) measured_offset_deg(dir, m, *rec);
            if (!rec)
                fail(
                    "{}: metadata.known_source names repeat {}, but it has no polarizer record at "
                    "{:g}°",
                    manifest_path(dir), repeat, pos.angle_deg);
            const RadianceFrame f = to_radiance(dir, m, *rec, radiometric);
            double sum = 0.0;
            std::size_t n = 0;
            for (std::size_t i = 0; i < f.radiance.size(); ++i) {
                if (radiometric.bad[i] != 0.0f || f.saturated[i]) continue;
                sum += (f.radiance[i] - pos.background[i]) / pos.tau[i];
                ++n;
            }
            if (n == 0) fail("{}: no good pixel in {}", manifest_path(dir), rec->file);
            meas.intensities.push_back(sum / static_cast<double>(n));
        }
        measurements.push_back(meas);
    }
    out.analyzer = estimate_analyzer(angles, measurements);
    out.analyzer_method = std::string("known-source least squares") +
                          (datasheet ? "; the datasheet values given were not used" : "");
    return out;
}

Image reduce_session(const fs::path& dir, const RadiometricCalibration& radiometric_in,
                     const PolarimetricCalibration* polarimetric,
                     const SessionReductionOptions& options) {
    const SessionManifest m = read_session(dir);
    if (!options.force_other_camera) check_same_camera(radiometric_in, m, dir);
    if (polarimetric)
        check_same_band(
            radiometric_in,
            "(made " + radiometric_in.created_utc + " for camera " + radiometric_in.camera_id + ")",
            *polarimetric, "the polarimetric calibration of " + polarimetric->session);
    RadiometricCalibration radiometric = radiometric_in;
    std::optional<OffsetUpdate> correction;
    if (options.update_offset && polarimetric)
        fail(
            "offset update together with a polarimetric calibration would remove the drift twice: "
            "the wire-grid "
            "background B(α), fitted the same night, already holds it; drop one of the two");
    if (options.update_offset) {
        // The reference must see the camera without the polarizer: a shutter, or a blackbody when
        // the polarizer was out of the beam.
        const bool polarizer = polarizer_in_beam(dir, m).value_or(false);
        const SessionRecord* ref = nullptr;
        for (const auto& r : m.records)
            if (is_temperature_reference(r) && r.kind == RecordKind::Shutter) ref = &r;
        if (!ref && !polarizer)
            for (const auto& r : m.records)
                if (is_temperature_reference(r)) ref = &r;
        if (!ref)
            fail(
                "{}: --update-offset needs a shutter record with a temperature (or a blackbody "
                "record taken "
                "without the polarizer); the session has none",
                manifest_path(dir));
        const BlackbodyFrame ref_frame = to_blackbody_frame(dir, m, *ref);
        update_offset(radiometric, ref_frame);
        correction = describe_offset_update(radiometric_in, radiometric, ref_frame);
    }
    if (options.drift_correction && polarimetric)
        fail(
            "drift correction together with a polarimetric calibration would remove the drift "
            "twice: the wire-grid "
            "background B(α) already holds the offset; drop one of the two");
    // Measured against the calibration in use (after --update-offset when both are asked for).
    std::optional<SessionOffsetDrift> drift;
    std::map<std::string, double> drift_by_file;
    if (options.drift_correction) {
        drift = session_offset_drift(dir, m, radiometric);
        for (std::size_t k = 0; k < drift->files.size(); ++k)
            drift_by_file[drift->files[k]] = drift->points[k].shift_counts;
    }
    std::map<int, Eigen::Vector3d> sources;
    if (m.metadata.contains("known_source")) sources = known_sources(dir, m, radiometric.band());

    // Scene records grouped by requested angle; repeats averaged, at the mean measured angle.
    struct Accumulator {
        std::vector<double> sum, var;
        std::vector<std::uint8_t> saturated;
        int n = 0;
        double offset_sum_deg = 0.0;  ///< measured − requested, summed over the repeats
        std::string source;
    };
    std::map<long, Accumulator> by_angle;
    std::string warnings;  // no silent extrapolation of the radiometric model (docs/calibration.md)
    double outside_range =
        0.0;  // the largest fraction of a frame's good pixels outside the calibrated range
    for (const auto& r : m.records) {
        if (r.kind != RecordKind::Polarizer || sources.count(r.repeat)) continue;
        throw_if_cancelled(options.cancel, "session reduction");
        const RadianceFrame f =
            to_radiance(dir, m, r, radiometric, drift ? drift_by_file.at(r.file) : 0.0);
        outside_range =
            std::max(outside_range, outside_calibrated_range_fraction(radiometric, f.radiance));
        if (const auto w = extrapolation_warning(radiometric, f.radiance, r.fpa_temperature_k))
            warnings += (warnings.empty() ? "" : "\n") + r.file + ": " + *w;
        const std::size_t sat =
            static_cast<std::size_t>(std::count(f.saturated.begin(), f.saturated.end(), 1));
        if (static_cast<double>(sat) >
            options.max_saturated_fraction * static_cast<double>(f.saturated.size()))
            fail(
                "{}: {} of {} pixels are saturated (counts ≥ {}); expected at most {:.3g}% — "
                "reduce the integration "
                "time",
                (dir / r.file).string(), sat, f.saturated.size(), *session_saturation_counts(m),
                100.0 * options.max_saturated_fraction);
        const double offset_deg = measured_offset_deg(dir, m, r);
        Accumulator& acc = by_angle[polarizer_angle_key(r.angle_deg_requested)];
        acc.offset_sum_deg += offset_deg;
        if (acc.n == 0) {
            acc.sum.assign(f.radiance.size(), 0.0);
            acc.var.assign(f.radiance.size(), 0.0);
            acc.saturated.assign(f.radiance.size(), 0);
            acc.source = (dir / r.file).string();
        }
        for (std::size_t i = 0; i < f.radiance.size(); ++i) {
            acc.sum[i] += f.radiance[i];
            acc.var[i] += static_cast<double>(f.sigma[i]) * f.sigma[i];
            acc.saturated[i] |= f.saturated[i];
        }
        ++acc.n;
    }
    if (by_angle.empty()) fail("{}: no polarizer (scene) records to reduce", manifest_path(dir));
    std::vector<AnalyzerImage> images;
    std::vector<double> angles;
    std::vector<std::uint8_t> saturated(radiometric.gain.size(), 0);
    for (const auto& [key, acc] : by_angle) {
        AnalyzerImage im;
        // The ideal analyzer sits where the stage read back; a calibrated one is indexed by nominal
        // angle and carries its own fitted axis angles.
        im.angle_deg = polarizer_angle_deg(key) + (polarimetric ? 0.0 : acc.offset_sum_deg / acc.n);
        im.source = acc.source;
        for (std::size_t i = 0; i < acc.sum.size(); ++i) {
            im.signal.push_back(static_cast<float>(acc.sum[i] / acc.n));
            im.signal_std.push_back(static_cast<float>(std::sqrt(acc.var[i]) / acc.n));
            saturated[i] |= acc.saturated[i];
        }
        angles.push_back(im.angle_deg);
        images.push_back(std::move(im));
    }
    const AnalyzerModel model =
        polarimetric ? polarimetric->analyzer : AnalyzerModel::ideal(angles);
    ReductionOptions reduction;
    reduction.include_slar = options.include_slar;
    reduction.cancel = options.cancel;
    Image out = reduce_stokes(images, radiometric.width, radiometric.height, model,
                              polarimetric ? &polarimetric->wire_grid : nullptr, reduction);
    int n_saturated = 0;
    for (std::size_t i = 0; i < saturated.size(); ++i)
        if (saturated[i]) {
            ++n_saturated;
            for (const auto& name : out.channel_names())
                out.channel(name)[i] = std::numeric_limits<float>::quiet_NaN();
        }
    auto& a = out.attributes();
    a["saturated_pixels"] = n_saturated;
    a["session"] = dir.string();
    a["camera_id"] = camera_id(m);
    a["offset_updated"] = options.update_offset ? 1 : 0;
    if (!warnings.empty()) a["calibration_warnings"] = warnings;
    StokesImageHeader header{.band_um = std::array{radiometric.band_lo_um, radiometric.band_hi_um}};
    if (!radiometric.temperatures_k.empty()) {
        const auto [t_lo, t_hi] = std::minmax_element(radiometric.temperatures_k.begin(),
                                                      radiometric.temperatures_k.end());
        header.calibration_range = CalibrationRangeAttribute{{*t_lo, *t_hi}, outside_range};
    }
    write_stokes_image_header(out, header);
    if (correction) {
        a["offset_update_source"] = correction->source;
        a["offset_update_mean_counts"] = correction->mean_counts;
        a["offset_update_sigma_counts"] = correction->sigma_counts;
        a["offset_update_sigma_mk"] = correction->sigma_mk;
    }
    if (drift) {
        std::vector<double> shift, sigma, time;
        for (const auto& p : drift->points) {
            shift.push_back(p.shift_counts);
            sigma.push_back(p.sigma_counts);
            time.push_back(p.time_s - drift->points.front().time_s);
        }
        a["drift_correction_source"] = drift->source;
        a["drift_offset_counts"] = shift;
        a["drift_offset_sigma_counts"] = sigma;
        a["drift_time_s"] = time;
        a["drift_records"] = fmt::format("{}", fmt::join(drift->files, "\n"));
    }
    a["analyzer"] = polarimetric ? polarimetric->analyzer_method
                                 : std::string("ideal (no polarimetric calibration)");
    return out;
}

}  // namespace tirpol::calibration
