#include "tirpol/acquisition/capture.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <thread>

#include "tirpol/acquisition/angles.h"
#include "tirpol/acquisition/frame_averager.h"
#include "tirpol/core/error.h"
#include "tirpol/core/progress.h"

namespace tirpol::acquisition {

namespace {

using namespace std::chrono;

milliseconds to_ms(double seconds) { return milliseconds(static_cast<std::int64_t>(std::ceil(seconds * 1000.0))); }

/// A failed step: the device error, which step, and how to continue.
[[noreturn]] void fail_step(const CaptureStep& step, std::size_t total, const char* device, const DeviceError& e,
                            const SessionWriter& session) {
    fail("step {}/{} ({}): {} {}: {}. {} of {} steps are recorded in {}; fix the cause and run again with --resume",
         step.index + 1, total, step.label, device, to_string(e.code), e.message, session.manifest().records.size(), total,
         session.dir().string());
}

template <typename T>
T check(Result<T> r, const CaptureStep& step, std::size_t total, const char* device, const SessionWriter& session) {
    if (!r) fail_step(step, total, device, r.error(), session);
    return std::move(r.value());
}

bool interrupted(const CaptureOptions& options) { return options.interrupt && options.interrupt->load(); }

/// A homing or move that returned: on an interruption (the stage was told to stop, or the signal
/// came while it failed) the run ends as "interrupted", resumable; any other error fails the step.
void check_motion(Status status, const char* motion, const CaptureStep& step, std::size_t total,
                  const SessionWriter& session, const CaptureOptions& options) {
    if (status) return;
    if (status.error().code == DeviceErrorCode::Stopped || interrupted(options))
        fail("interrupted during {} (step {}/{}, {}): {}; {} of {} steps are recorded in {}; run again with --resume",
             motion, step.index + 1, total, step.label, status.error().message, session.manifest().records.size(),
             total, session.dir().string());
    fail_step(step, total, "stage", status.error(), session);
}

/// Waits `seconds` after a move, returning early (false) on an interruption: a long settle_s must
/// not hold Ctrl-C back.
bool settle(double seconds, const CaptureOptions& options) {
    const auto end = steady_clock::now() + duration_cast<steady_clock::duration>(duration<double>(seconds));
    for (auto now = steady_clock::now(); now < end; now = steady_clock::now()) {
        if (interrupted(options)) return false;
        std::this_thread::sleep_for(std::min<steady_clock::duration>(milliseconds(20), end - now));
    }
    return !interrupted(options);
}

}  // namespace

SessionManifest new_session_manifest(const CameraInfo& camera, const StageInfo& stage, const CapturePlan& plan) {
    SessionManifest m;
    m.camera = {camera.uri, camera.vendor, camera.model, camera.serial, camera.pixel_format, camera.width, camera.height,
                camera.bits_per_pixel, camera.frame_rate_hz, camera.planck_constants};
    m.stage = {stage.uri, stage.vendor, stage.model, stage.serial, stage.firmware, stage.counts_per_degree};
    m.plan = plan.to_json();
    m.metadata = plan.metadata;
    return m;
}

void check_resumable(const SessionManifest& m, const CameraInfo& camera, const CapturePlan& plan) {
    if (m.plan != plan.to_json())
        fail("the plan differs from the one this session was started with (session: {}; now: {}); resume with the same plan",
             m.plan.dump(), plan.to_json().dump());
    if (m.camera.width != camera.width || m.camera.height != camera.height || m.camera.pixel_format != camera.pixel_format)
        fail("the camera delivers {}×{} {}, the session was started with {}×{} {}; resume with the same camera settings",
             camera.width, camera.height, camera.pixel_format, m.camera.width, m.camera.height, m.camera.pixel_format);
}

CaptureSummary run_capture(Camera& camera, Stage& stage, const CapturePlan& plan, SessionWriter& session,
                           const CaptureOptions& options) {
    const auto steps = plan_steps(plan);
    CaptureSummary summary;
    summary.steps_total = steps.size();
    std::vector<const CaptureStep*> todo;
    for (const auto& s : steps)
        if (!session.has_record(s.file)) todo.push_back(&s);
    summary.steps_already_recorded = steps.size() - todo.size();
    if (todo.empty()) {
        if (!session.manifest().complete) session.mark_complete();
        return summary;
    }
    const std::size_t total = steps.size();
    const CaptureStep& first = *todo.front();

    check(camera.start(), first, total, "camera", session);
    if (!stage.is_homed()) {
        spdlog::info("homing the stage {}", stage.info().uri);
        check_motion(stage.home(to_ms(plan.home_timeout_s)), "homing", first, total, session, options);
    }
    std::unique_ptr<ProgressReporter> progress;
    if (options.progress_stream) progress = std::make_unique<ProgressReporter>("acquire", todo.size(), options.progress_stream);

    for (const CaptureStep* step : todo) {
        if (options.interrupt && options.interrupt->load())
            fail("interrupted before step {}/{} ({}); {} of {} steps are recorded in {}; run again with --resume", step->index + 1,
                 total, step->label, session.manifest().records.size(), total, session.dir().string());
        if (step->kind != RecordKind::Polarizer && options.prompt) {
            const std::string instruction =
                step->kind == RecordKind::Blackbody
                    ? fmt::format("Place the blackbody at {:.2f} K ({:.2f} °C) in front of the camera, filling the field of view", *step->temperature_k, *step->temperature_k - 273.15)
                    : std::string("Close the shutter (or cover the lens with a uniform cover)");
            if (!options.prompt(instruction))
                fail("stopped by the operator before step {}/{} ({}); run again with --resume to continue", step->index + 1, total, step->label);
        }
        check_motion(stage.move_absolute(step->angle_deg, to_ms(plan.move_timeout_s)), "the move", *step, total,
                     session, options);
        if (!settle(plan.settle_s, options))
            fail(
                "interrupted while the stage settled (step {}/{}, {}); {} of {} steps are recorded in {}; run again "
                "with --resume",
                step->index + 1, total, step->label, session.manifest().records.size(), total, session.dir().string());
        const double measured = check(stage.position_deg(), *step, total, "stage", session);
        if (std::abs(angle_difference_deg(measured, step->angle_deg)) > plan.angle_tolerance_deg)
            fail_step(*step, total, "stage",
                      {DeviceErrorCode::DeviceFault, fmt::format("reads {:.4f}° after moving to {:.4f}° (tolerance {}°)", measured,
                                                                 step->angle_deg, plan.angle_tolerance_deg)},
                      session);

        const std::uint64_t dropped_before = camera.statistics().dropped;
        FrameAverager averager;
        SessionRecord record;
        double fpa_sum = 0.0;
        int fpa_count = 0;
        for (int i = 0; i < step->frames; ++i) {
            if (options.interrupt && options.interrupt->load())
                fail("interrupted during step {}/{} ({}); its frames are discarded, {} of {} steps are recorded in {}; run again with --resume",
                     step->index + 1, total, step->label, session.manifest().records.size(), total, session.dir().string());
            const Frame frame = check(camera.grab(to_ms(plan.frame_timeout_s)), *step, total, "camera", session);
            averager.add(frame);
            if (i == 0) record.first_timestamp_ns = frame.host_timestamp_ns;
            record.last_timestamp_ns = frame.host_timestamp_ns;
            if (frame.fpa_temperature_k) {
                fpa_sum += *frame.fpa_temperature_k;
                ++fpa_count;
            }
        }
        if (fpa_count > 0) record.fpa_temperature_k = fpa_sum / fpa_count;
        else record.fpa_temperature_k = camera.device_temperature_k();
        record.kind = step->kind;
        record.file = step->file;
        record.angle_deg_requested = step->angle_deg;
        record.angle_deg_measured = measured;
        record.repeat = step->repeat;
        record.blackbody_temperature_k = step->temperature_k;
        record.frames = step->frames;
        record.dropped = static_cast<std::int64_t>(camera.statistics().dropped - dropped_before);
        session.add_record(record, averager.to_image());
        summary.steps_recorded++;
        summary.frames += static_cast<std::uint64_t>(step->frames);
        summary.dropped += static_cast<std::uint64_t>(record.dropped);
        if (progress) progress->advance();
    }
    if (progress) progress->finish();
    if (auto s = camera.stop(); !s) spdlog::warn("stopping the camera: {}", s.error().message);
    session.mark_complete();
    return summary;
}

}  // namespace tirpol::acquisition
