#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>

#include "tirpol/acquisition/capture.h"
#include "tirpol/core/error.h"
#include "tirpol/core/interrupt_signals.h"
#include "tirpol/core/output_guard.h"

namespace tirpol::acquisition {

namespace {
// The FFC schedule the options ask for, or none; checked before any device is opened.
std::optional<FfcOptions> ffc_options(const AcquisitionOptions& o) {
    const bool link = !o.camera_control_uri.empty();
    if (o.ffc_schedule == "detect" && link)
        fail(
            "--ffc detect watches the frames only; leave out --camera-control, or choose a "
            "schedule for the link");
    if (o.ffc_schedule.empty() && !link) return std::nullopt;
    return parse_ffc_schedule(o.ffc_schedule.empty() ? "every-cycle" : o.ffc_schedule);
}

[[noreturn]] void exit_overdue(const std::filesystem::path& session) {
    std::fprintf(stderr,
                 "\ntirpol acquire: interrupted; a device did not return within %.1f s, exiting "
                 "now. Every step recorded so far is kept in %s; run again with --resume to "
                 "continue\n",
                 std::chrono::duration<double>(kAcquisitionInterruptGrace).count(),
                 session.c_str());
    std::_Exit(1);
}
}  // namespace

AcquisitionResult run_acquisition(const AcquisitionOptions& o) {
    // The session writer refuses a non-empty folder (unless resuming): only the inputs are checked
    // here.
    OutputGuard().input(o.plan, "PLAN").output_session(o.session, "--output").check(false);
    const CapturePlan plan = CapturePlan::load(o.plan);
    if (o.resume && !std::filesystem::exists(o.session / kSessionManifestName))
        fail("{}: no session to resume here (no {}); leave out --resume to start one",
             o.session.string(), kSessionManifestName);
    std::optional<FfcOptions> ffc = ffc_options(o);

    // Handlers first, so an interruption at any point after this leaves through the same clean
    // path. First Ctrl-C: the stage is told to stop and the run ends after the current frame. A
    // second one ends the process at once, which is safe too: every session write is atomic.
    const InterruptSignals interrupt;
    // Declared before `stage`, so it stops watching before the stage goes.
    std::unique_ptr<Stage> stage;
    StopOnInterrupt stop_on_interrupt(interrupt.flag(), kAcquisitionInterruptGrace,
                                      [session = o.session] { exit_overdue(session); });
    auto camera = open_camera(o.camera_uri).value_or_throw();
    stage = couple_simulated_polarizer(*camera, open_stage(o.stage_uri).value_or_throw());
    stop_on_interrupt.watch(stage.get());
    std::unique_ptr<BlackbodyController> blackbody;
    if (!o.blackbody_uri.empty()) blackbody = open_blackbody(o.blackbody_uri).value_or_throw();
    const BlackbodyInfo blackbody_info = blackbody ? blackbody->info() : BlackbodyInfo{};

    SessionWriter session = open_capture_session(o.session, camera->info(), stage->info(), plan,
                                                 o.resume, blackbody ? &blackbody_info : nullptr);
    AcquisitionResult result;
    result.session = o.session;
    for (const auto& file : session.adopted_files()) {
        spdlog::info("recovered {} (written just before the interruption)", file);
        result.recovered.push_back(file);
    }

    std::unique_ptr<FfcControl> camera_control;
    if (!o.camera_control_uri.empty())
        camera_control = open_ffc_control(o.camera_control_uri).value_or_throw();
    if (ffc) ffc->control = camera_control.get();
    result.ffc = ffc.has_value();

    CaptureOptions options;
    options.ffc = ffc ? &*ffc : nullptr;
    options.prompt = o.prompt;
    options.interrupt = &interrupt.flag();
    options.blackbody = blackbody.get();
    result.summary = run_capture(*camera, *stage, plan, session, options);
    return result;
}

std::string acquisition_summary_text(const AcquisitionResult& r) {
    const CaptureSummary& s = r.summary;
    std::string text = fmt::format(
        "session complete: {}\n  steps: {} ({} recorded now, {} were already there)\n  frames "
        "averaged now: {}, dropped by the camera: {}\n",
        r.session.string(), s.steps_total, s.steps_recorded, s.steps_already_recorded, s.frames,
        s.dropped);
    if (r.ffc)
        text += fmt::format(
            "  flat-field corrections: {} scheduled between cycles, {} detected inside a cycle "
            "(retaken)\n",
            s.ffc_scheduled, s.ffc_detected);
    return text;
}

}  // namespace tirpol::acquisition
