#include "tirpol/acquisition/capture.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <thread>

#include "capture/blackbody_step.h"
#include "capture/ffc_guard.h"
#include "capture/record_writer.h"
#include "tirpol/acquisition/frame_gate.h"
#include "tirpol/acquisition/internal/angles.h"
#include "tirpol/core/error.h"
#include "tirpol/core/log.h"
#include "tirpol/core/radiometry.h"

namespace tirpol::acquisition {

namespace {

using namespace std::chrono;

milliseconds to_ms(double seconds) {
    return milliseconds(static_cast<std::int64_t>(std::ceil(seconds * 1000.0)));
}

bool interrupted(const CaptureOptions& options) {
    return options.interrupt && options.interrupt->load();
}

/// Sleeps until the host clock reaches `until_ns`, returning early (false) on an interruption: a
/// long settle_s must not hold Ctrl-C back.
bool sleep_until_host_ns(std::int64_t until_ns, const CaptureOptions& options) {
    for (std::int64_t now = host_realtime_ns(); now < until_ns; now = host_realtime_ns()) {
        if (interrupted(options)) return false;
        std::this_thread::sleep_for(
            std::min(nanoseconds(milliseconds(20)), nanoseconds(until_ns - now)));
    }
    return !interrupted(options);
}

}  // namespace

SessionManifest new_session_manifest(const CameraInfo& camera, const StageInfo& stage,
                                     const CapturePlan& plan, const BlackbodyInfo* blackbody) {
    SessionManifest m;
    // frame_rate_hz stays null until the capture loop has measured what the camera delivers.
    m.camera = {camera.uri,
                camera.vendor,
                camera.model,
                camera.serial,
                camera.pixel_format,
                camera.width,
                camera.height,
                camera.bits_per_pixel,
                std::nullopt,
                camera.planck_constants,
                camera.microgrid_pattern_deg};
    m.stage = {stage.uri,    stage.vendor,   stage.model,
               stage.serial, stage.firmware, stage.counts_per_degree};
    if (blackbody)
        m.blackbody_controller =
            SessionBlackbodyController{blackbody->uri, blackbody->vendor, blackbody->model,
                                       blackbody->serial, blackbody->firmware};
    m.plan = plan.to_json();
    m.metadata = plan.metadata;
    return m;
}

void check_resumable(const SessionManifest& m, const CameraInfo& camera, const CapturePlan& plan) {
    if (m.plan != plan.to_json())
        fail(
            "the plan differs from the one this session was started with (session: {}; now: {}); "
            "resume with the same plan",
            m.plan.dump(), plan.to_json().dump());
    if (m.camera.width != camera.width || m.camera.height != camera.height ||
        m.camera.pixel_format != camera.pixel_format)
        fail(
            "the camera delivers {}×{} {}, the session was started with {}×{} {}; resume with the "
            "same camera settings",
            camera.width, camera.height, camera.pixel_format, m.camera.width, m.camera.height,
            m.camera.pixel_format);
    if (m.camera.microgrid_pattern_deg != camera.microgrid_pattern_deg)
        fail(
            "the camera's microgrid pattern ({}) differs from the session's ({}); resume with the "
            "same camera settings",
            camera.microgrid_pattern_deg
                ? fmt::format("{}", fmt::join(*camera.microgrid_pattern_deg, ","))
                : "none",
            m.camera.microgrid_pattern_deg
                ? fmt::format("{}", fmt::join(*m.camera.microgrid_pattern_deg, ","))
                : "none");
}

std::uintmax_t session_bytes_needed(int width, int height, std::size_t steps) {
    // Per step one EXR of two FLOAT planes (counts, counts_std): its uncompressed size bounds the
    // ZIP output (noise compresses poorly); plus the header and a manifest rewrite. One extra frame
    // covers the staged copy that exists while a record is placed.
    const std::uintmax_t per_step =
        static_cast<std::uintmax_t>(width) * static_cast<std::uintmax_t>(height) * 2u * 4u +
        64u * 1024u;
    return per_step * (steps + 1) + 1024u * 1024u;
}

void check_free_space(const std::filesystem::path& dir, int width, int height, std::size_t steps) {
    std::error_code ec;
    const auto space = std::filesystem::space(dir, ec);
    if (ec)
        return;  // cannot tell (e.g. a file system without statvfs): the write errors will say it
    const std::uintmax_t needed = session_bytes_needed(width, height, steps);
    if (space.available < needed)
        fail(
            "{}: {} steps of {}×{} frames need about {:.1f} MB, only {:.1f} MB are free on that "
            "file system; free "
            "space (or choose another directory) and run again{}",
            dir.string(), steps, width, height, static_cast<double>(needed) / 1e6,
            static_cast<double>(space.available) / 1e6,
            std::filesystem::exists(dir / kSessionManifestName) ? " with --resume" : "");
}

CaptureSummary run_capture(Camera& camera, Stage& stage, const CapturePlan& plan,
                           SessionWriter& session, const CaptureOptions& options) {
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
    if (plan_uses_blackbody_controller(plan) && !options.blackbody)
        fail(
            "the plan sets blackbody temperatures (references[].controller) but no blackbody "
            "controller was given (tirpol acquire "
            "--blackbody URI); nothing was recorded");
    std::optional<double> settled_set_point_k;  // the controller's set-point reached in this run
    auto report = [&](CaptureProgress::Event event, const CaptureStep& step, int frames_kept,
                      std::uint64_t frame_id) {
        if (options.on_progress)
            options.on_progress({event, &step, total,
                                 summary.steps_already_recorded + summary.steps_recorded,
                                 frames_kept, frame_id});
    };
    check_free_space(session.dir(), session.manifest().camera.width,
                     session.manifest().camera.height, todo.size());

    detail::RecordWriter writer(session);
    auto recorded = [&] { return writer.records(); };
    auto step_failed = [&](const CaptureStep& step, const char* device, const DeviceError& e) {
        fail(
            "step {}/{} ({}): {} {}: {}. {} of {} steps are recorded in {}; fix the cause and run "
            "again with --resume",
            step.index + 1, total, step.label, device, to_string(e.code), e.message, recorded(),
            total, session.dir().string());
    };
    auto check = [&]<typename T>(Result<T> r, const CaptureStep& step, const char* device) -> T {
        if (!r) step_failed(step, device, r.error());
        return std::move(r.value());
    };
    // A homing or move that returned: on an interruption (the stage was told to stop, or the signal
    // came while it failed) the run ends as "interrupted", resumable; any other error fails the
    // step.
    auto check_motion = [&](Status status, const char* motion, const CaptureStep& step) {
        if (status) return;
        if (status.error().code == DeviceErrorCode::Stopped || interrupted(options))
            fail(
                "interrupted during {} (step {}/{}, {}): {}; {} of {} steps are recorded in {}; "
                "run again with --resume",
                motion, step.index + 1, total, step.label, status.error().message, recorded(),
                total, session.dir().string());
        step_failed(step, "stage", status.error());
    };
    // Names the step whose record failed to write (the writer runs behind: the step being captured
    // when its error surfaces is usually a later one).
    auto write_failed = [&](const CaptureStep& current, const Error& e) {
        const std::string file = writer.failed_file();
        const auto failed = std::find_if(todo.begin(), todo.end(),
                                         [&](const CaptureStep* s) { return s->file == file; });
        const CaptureStep& step = failed != todo.end() ? **failed : current;
        fail(
            "step {}/{} ({}): writing the session failed: {}. {} of {} steps are recorded in {}; "
            "free disk space if it "
            "is full and run again with --resume",
            step.index + 1, total, step.label, e.what(), session.manifest().records.size(), total,
            session.dir().string());
    };

    // One-direction approach: the last leg of every move turns the same way (negative, as homing
    // ends), so a mount with backlash sits at the same side of its play at every angle.
    auto move_to = [&](double angle_deg, const CaptureStep& step) {
        if (plan.approach_overshoot_deg > 0)
            check_motion(stage.move_absolute(angle_deg + plan.approach_overshoot_deg,
                                             to_ms(plan.move_timeout_s)),
                         "the approach move", step);
        check_motion(stage.move_absolute(angle_deg, to_ms(plan.move_timeout_s)), "the move", step);
    };
    // Lost-step check for stages whose read-back is their step counter: at counted zero the home
    // sensor must be active. Steps recorded since the last passing check are named when it fails.
    std::size_t verified_up_to = 0;  // steps (plan index) taken before the last passing check
    bool home_sensor_readable = true;
    auto home_check = [&](const CaptureStep& step, std::size_t next_index) {
        if (plan.home_check_every <= 0 || !home_sensor_readable) return;
        move_to(0.0, step);
        auto active = stage.home_sensor_active();
        if (!active && active.error().code == DeviceErrorCode::NotSupported) {
            spdlog::info("{}; lost steps are caught by the angle read-back only",
                         active.error().message);
            home_sensor_readable = false;
            return;
        }
        const bool passed = check(std::move(active), step, "stage");
        // In the session before anything else can fail: a reviewer sees which steps a failed check
        // puts in doubt, and when the passing ones were made.
        try {
            writer.flush();  // the session is written by one thread at a time
            session.add_home_check(
                HomeCheck{host_realtime_ns(), passed, static_cast<int>(next_index),
                          static_cast<std::int64_t>(next_index - verified_up_to)});
        } catch (const Error& e) {
            write_failed(step, e);
        }
        if (!passed) {
            const Status rehomed = stage.home(to_ms(plan.home_timeout_s));
            step_failed(
                step, "stage",
                {DeviceErrorCode::DeviceFault,
                 fmt::format("lost steps: at counted 0° the home sensor is not active, so "
                             "the mount is not where the step counter says; the steps "
                             "from {} to {} were taken after the last passing check and "
                             "their angles are uncertain (remove them from the session "
                             "to take them again); the stage {}",
                             verified_up_to + 1, next_index,
                             rehomed ? std::string("was homed again")
                                     : "could not be homed again: " + rehomed.error().message)});
        }
        ++summary.home_checks;
        verified_up_to = next_index;
        spdlog::info("home check before step {}: the home sensor is active at counted 0°",
                     next_index + 1);
    };

    check(camera.start(), first, "camera");
    // A core that reports through its frames (a Lepton's telemetry) is heard only when frames are
    // grabbed: while its link waits for an FFC, it pulls them through this thread.
    FfcControl* const ffc_link = options.ffc ? options.ffc->control : nullptr;
    struct FramePullLease {
        FfcControl* link;
        ~FramePullLease() {
            if (link) link->set_frame_pull({});
        }
    } pull_lease{ffc_link};
    if (ffc_link)
        ffc_link->set_frame_pull([&camera, ffc_link] {
            if (auto f = camera.grab(std::chrono::milliseconds(100)))
                ffc_link->observe_frame(f.value());
        });
    if (!stage.is_homed()) {
        spdlog::info("homing the stage {}", stage.info().uri);
        check_motion(stage.home(to_ms(plan.home_timeout_s)), "homing", first);
    }
    std::unique_ptr<ProgressReporter> progress;
    if (options.progress_stream)
        progress =
            std::make_unique<ProgressReporter>("acquire", todo.size(), options.progress_stream);

    FrameGate gate(camera.info().frame_rate_hz);
    const auto settle_ns = static_cast<std::int64_t>(std::llround(plan.settle_s * 1e9));
    const auto frame_timeout_ns =
        static_cast<std::int64_t>(std::llround(plan.frame_timeout_s * 1e9));
    // Flat-field corrections: a cycle is the run of polarizer steps of one repeat; its records are
    // held until the cycle proves free of FFCs, and it is taken again from its first step when it
    // is not.
    std::optional<detail::FfcGuard> guard;
    if (options.ffc) guard.emplace(*options.ffc);
    auto in_cycle = [&](std::size_t i) { return guard && todo[i]->kind == RecordKind::Polarizer; };
    auto same_cycle = [&](std::size_t a, std::size_t b) {
        return in_cycle(a) && in_cycle(b) && todo[a]->repeat == todo[b]->repeat;
    };
    struct HeldRecord {
        const CaptureStep* step;
        SessionRecord record;
        Image image;
        std::optional<double> rate_hz;
    };
    std::vector<HeldRecord> held;
    std::size_t cycle_start = 0;
    int cycles_started = 0, cycle_attempt = 0;
    auto commit = [&](const CaptureStep& step, SessionRecord record, Image image,
                      std::optional<double> rate_hz) {
        try {
            writer.submit(record, std::move(image), rate_hz);
        } catch (const Error& e) {
            write_failed(step, e);
        }
        summary.steps_recorded++;
        summary.frames += static_cast<std::uint64_t>(step.frames);
        summary.dropped += static_cast<std::uint64_t>(record.dropped);
        summary.stale_discarded +=
            static_cast<std::uint64_t>(record.timing->stale_frames_discarded);
        if (progress) progress->advance();
        report(CaptureProgress::Event::StepRecorded, step, step.frames, 0);
    };
    auto record_ffc = [&](const CaptureStep& step, const FfcEvent& event) {
        try {
            writer.flush();  // the session is written by one thread at a time
            session.add_ffc_event(event);
        } catch (const Error& e) {
            write_failed(step, e);
        }
        spdlog::info("{} FFC (cycle {}): {}", to_string(event.kind), event.repeat + 1,
                     event.reason);
    };
    // An FFC inside the cycle: its held records are dropped and the cycle starts again; returns the
    // index of the cycle's first step.
    auto retake_cycle = [&](const CaptureStep& step, const FfcEvent& event) {
        record_ffc(step, event);
        ++summary.ffc_detected;
        held.clear();
        guard->abandon_cycle();
        if (++cycle_attempt >= options.ffc->max_cycle_attempts)
            fail(
                "step {}/{} ({}): an FFC fell inside polarizer cycle {} in each of {} attempts "
                "(last: {}); {} of {} "
                "steps are recorded in {}; put the core in manual FFC (or give its control link) "
                "and run again "
                "with --resume",
                step.index + 1, total, step.label, step.repeat + 1, cycle_attempt, event.reason,
                recorded(), total, session.dir().string());
        const auto pause_ns = static_cast<std::int64_t>(options.ffc->detection_pause_s * 1e9);
        if (!options.ffc->control && !sleep_until_host_ns(host_realtime_ns() + pause_ns, options))
            fail(
                "interrupted while waiting for an FFC to end (step {}/{}, {}); {} of {} steps are "
                "recorded in {}; run "
                "again with --resume",
                step.index + 1, total, step.label, recorded(), total, session.dir().string());
        return cycle_start;
    };
    verified_up_to = first.index;
    bool polarizer_steps_taken = false;
    for (std::size_t ti = 0; ti < todo.size(); ++ti) {
        const CaptureStep* step = todo[ti];
        const bool cycle_begins = step->kind == RecordKind::Polarizer &&
                                  (ti == 0 || todo[ti - 1]->kind != RecordKind::Polarizer ||
                                   todo[ti - 1]->repeat != step->repeat);
        if (cycle_begins && step->repeat > 0 && plan.home_check_every > 0 &&
            step->repeat % plan.home_check_every == 0 && polarizer_steps_taken)
            home_check(*step, step->index);
        if (step->kind == RecordKind::Polarizer) polarizer_steps_taken = true;
        if (in_cycle(ti) && (ti == 0 || !same_cycle(ti - 1, ti))) {
            const bool retry = ti == cycle_start && cycle_attempt > 0;
            if (!retry) {
                cycle_start = ti;
                cycle_attempt = 0;
            }
            auto scheduled = guard->before_cycle(step->repeat, cycles_started, retry);
            if (!scheduled) step_failed(*step, "camera control link", scheduled.error());
            if (scheduled.value()) {
                record_ffc(*step, *scheduled.value());
                ++summary.ffc_scheduled;
            }
            if (!retry) ++cycles_started;
        }
        if (in_cycle(ti)) guard->begin_step();
        if (interrupted(options))
            fail(
                "interrupted before step {}/{} ({}); {} of {} steps are recorded in {}; run again "
                "with --resume",
                step->index + 1, total, step->label, recorded(), total, session.dir().string());
        std::optional<detail::BlackbodyStep> blackbody;
        if (step->blackbody_control) {
            blackbody.emplace(*options.blackbody, *step, settled_set_point_k);
            if (auto reached = blackbody->reach_set_point([&] { return interrupted(options); });
                !reached) {
                if (reached.error().code == DeviceErrorCode::Stopped)
                    fail(
                        "interrupted while the blackbody settled (step {}/{}, {}); {} of {} steps "
                        "are recorded in {}; run again with --resume",
                        step->index + 1, total, step->label, recorded(), total,
                        session.dir().string());
                step_failed(*step, "blackbody", reached.error());
            }
        } else if ((step->kind != RecordKind::Polarizer || step->after_shutter) && options.prompt) {
            const std::string instruction =
                step->kind == RecordKind::Polarizer
                    ? std::string("Open the shutter (uncover the lens) for the scene")
                : step->kind == RecordKind::Blackbody
                    ? fmt::format(
                          "Place the blackbody at {:.2f} K ({:.2f} °C) in front of the camera, "
                          "filling the field of view",
                          *step->temperature_k, *step->temperature_k - kZeroCelsiusK)
                    : std::string("Close the shutter (or cover the lens with a uniform cover)");
            if (!options.prompt(instruction))
                fail(
                    "stopped by the operator before step {}/{} ({}); run again with --resume to "
                    "continue",
                    step->index + 1, total, step->label);
        }
        StepTiming timing;
        timing.move_start_ns = host_realtime_ns();
        move_to(step->angle_deg, *step);
        timing.move_end_ns = host_realtime_ns();
        timing.settle_end_ns = timing.move_end_ns + settle_ns;
        if (!sleep_until_host_ns(timing.settle_end_ns, options))
            fail(
                "interrupted while the stage settled (step {}/{}, {}); {} of {} steps are recorded "
                "in {}; run again with "
                "--resume",
                step->index + 1, total, step->label, recorded(), total, session.dir().string());
        auto read_angle = [&](const char* when) {
            const double a = check(stage.position_deg(), *step, "stage");
            if (std::abs(angle_difference_deg(a, step->angle_deg)) > plan.angle_tolerance_deg)
                step_failed(
                    *step, "stage",
                    {DeviceErrorCode::DeviceFault,
                     fmt::format(
                         "reads {:.4f}° {} (moved to {:.4f}°, tolerance {}°){}", a, when,
                         step->angle_deg, plan.angle_tolerance_deg,
                         std::string(when) == "after the frames"
                             ? ": the stage drifted during the step, its frames are discarded"
                             : "")});
            return a;
        };
        timing.angle_deg_before_frames = read_angle("after settling");

        // Frames queued since the move began (a free-running camera never stops) come first: drain
        // them, keeping only frames exposed after the settle end.
        // Drops among the kept frames only: frames lost while nobody grabbed during the move (a
        // full queue) are counted by the camera too, but they belong to no step.
        std::uint64_t dropped_before = 0;
        FrameAverager averager;
        SessionRecord record;
        double fpa_sum = 0.0;
        int fpa_count = 0;
        std::optional<FfcEvent> spoiled;  // an FFC seen in this step's frames
        FrameAudit audit;
        const std::uint64_t incomplete_before = camera.statistics().incomplete;
        FfcControl* const link = ffc_link;
        bool frames_carry_telemetry = false;
        if (link) audit.core_before = check(link->core_state(), *step, "camera control link");
        while (averager.count() < static_cast<std::uint64_t>(step->frames)) {
            if (interrupted(options))
                fail(
                    "interrupted during step {}/{} ({}); its frames are discarded, {} of {} steps "
                    "are recorded in {}; run again with --resume",
                    step->index + 1, total, step->label, recorded(), total, session.dir().string());
            if (blackbody) check(blackbody->poll_if_due(), *step, "blackbody");
            const Frame frame = check(camera.grab(to_ms(plan.frame_timeout_s)), *step, "camera");
            if (link) link->observe_frame(frame);
            if (!gate.exposed_after(frame, timing.settle_end_ns)) {
                ++timing.stale_frames_discarded;
                if (host_realtime_ns() - timing.settle_end_ns >
                    frame_timeout_ns + gate.exposure_window_ns())
                    step_failed(*step, "camera",
                                {DeviceErrorCode::BadReply,
                                 fmt::format("for {:g} s after the stage settled every frame was "
                                             "stamped before it (frame {} received {} ns "
                                             "before the settle end, {} discarded): the camera's "
                                             "timestamps are not on the host clock",
                                             plan.frame_timeout_s, frame.frame_id,
                                             timing.settle_end_ns - frame.host_timestamp_ns,
                                             timing.stale_frames_discarded)});
                continue;
            }
            if (in_cycle(ti)) {
                if (auto why = guard->observe(frame)) {
                    spoiled = guard->detected(
                        step->repeat,
                        fmt::format("step {} ({}): {}", step->index + 1, step->label, *why));
                    break;
                }
            }
            averager.add(frame);
            audit.frame_id.push_back(static_cast<std::int64_t>(frame.frame_id));
            audit.device_timestamp_ns.push_back(frame.device_timestamp_ns);
            audit.host_timestamp_ns.push_back(frame.host_timestamp_ns);
            audit.fpa_temperature_k.push_back(frame.fpa_temperature_k);
            frames_carry_telemetry = frames_carry_telemetry || frame.telemetry.has_value();
            audit.device_frame_counter.push_back(
                frame.telemetry ? std::optional<std::int64_t>(frame.telemetry->device_frame_counter)
                                : std::nullopt);
            audit.ffc_state.push_back(
                frame.telemetry ? std::optional<int>(frame.telemetry->ffc_state) : std::nullopt);
            report(CaptureProgress::Event::Frame, *step, static_cast<int>(averager.count()),
                   frame.frame_id);
            if (averager.count() == 1) {
                record.first_timestamp_ns = frame.host_timestamp_ns;
                dropped_before = camera.statistics().dropped;
            }
            record.last_timestamp_ns = frame.host_timestamp_ns;
            if (frame.fpa_temperature_k) {
                fpa_sum += *frame.fpa_temperature_k;
                ++fpa_count;
            }
        }
        if (spoiled) {
            ti = retake_cycle(*step, *spoiled) -
                 1;  // the loop's ++ti brings it to the cycle's first step
            continue;
        }
        if (blackbody) check(blackbody->finish(), *step, "blackbody");
        timing.angle_deg_after_frames = read_angle("after the frames");
        if (std::abs(angle_difference_deg(timing.angle_deg_after_frames,
                                          timing.angle_deg_before_frames)) >
            plan.angle_tolerance_deg)
            step_failed(*step, "stage",
                        {DeviceErrorCode::DeviceFault,
                         fmt::format("moved from {:.4f}° to {:.4f}° while its frames were taken "
                                     "(tolerance {}°): the stage drifted "
                                     "during the step, its frames are discarded",
                                     timing.angle_deg_before_frames, timing.angle_deg_after_frames,
                                     plan.angle_tolerance_deg)});
        timing.exposure_window_ns = gate.exposure_window_ns();
        if (fpa_count > 0)
            record.fpa_temperature_k = fpa_sum / fpa_count;
        else
            record.fpa_temperature_k = camera.device_temperature_k();
        record.kind = step->kind;
        record.file = step->file;
        record.angle_deg_requested = step->angle_deg;
        record.angle_deg_measured =
            wrap_degrees(timing.angle_deg_before_frames +
                         0.5 * angle_difference_deg(timing.angle_deg_after_frames,
                                                    timing.angle_deg_before_frames));
        record.repeat = step->repeat;
        record.blackbody_temperature_k = step->temperature_k;
        if (blackbody) {
            // What the controller read during the frames, not the set-point: the calibration uses
            // it.
            record.blackbody_readings = blackbody->readings();
            record.blackbody_temperature_k = record.blackbody_readings->mean_k;
        }
        record.frames = step->frames;
        record.dropped = static_cast<std::int64_t>(camera.statistics().dropped - dropped_before);
        record.timing = timing;
        audit.incomplete =
            static_cast<std::int64_t>(camera.statistics().incomplete - incomplete_before);
        if (link) audit.core_after = check(link->core_state(), *step, "camera control link");
        if (!frames_carry_telemetry) {
            audit.device_frame_counter.clear();
            audit.ffc_state.clear();
        }
        record.audit = std::move(audit);
        if (!in_cycle(ti)) {
            commit(*step, record, averager.to_image(), gate.delivered_rate_hz());
            continue;
        }
        guard->end_step(step->angle_deg);
        held.push_back({step, record, averager.to_image(), gate.delivered_rate_hz()});
        if (ti + 1 < todo.size() && same_cycle(ti, ti + 1)) continue;
        auto found = guard->end_cycle(step->repeat);
        if (!found) step_failed(*step, "camera control link", found.error());
        if (found.value()) {
            ti = retake_cycle(*step, *found.value()) - 1;
            continue;
        }
        for (auto& h : held) commit(*h.step, std::move(h.record), std::move(h.image), h.rate_hz);
        held.clear();
        cycle_attempt = 0;
    }
    try {
        writer.flush();
    } catch (const Error& e) {
        write_failed(*todo.back(), e);
    }
    if (polarizer_steps_taken) home_check(*todo.back(), todo.back()->index + 1);
    if (progress) progress->finish();
    if (auto s = camera.stop(); !s) spdlog::warn("stopping the camera: {}", s.error().message);
    summary.delivered_frame_rate_hz = gate.delivered_rate_hz();
    if (summary.delivered_frame_rate_hz)
        session.set_camera_frame_rate(*summary.delivered_frame_rate_hz);
    session.mark_complete();
    return summary;
}

}  // namespace tirpol::acquisition
