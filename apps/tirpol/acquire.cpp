// `tirpol acquire PLAN.yaml --camera URI --stage URI [--blackbody URI] [--camera-control URI]
// [--ffc SCHEDULE]
//  -o DIR [--resume] [--non-interactive]`:
// runs a capture plan into a session directory (docs/acquisition-stages.md,
// docs/session-format.md). Exit codes: 0 session complete; 1 an error (bad plan or URI, device
// fault, interruption — the message says how many steps are recorded; continue with --resume); 2
// bad command-line usage.

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "cli.h"
#include "tirpol/acquisition/blackbody.h"
#include "tirpol/acquisition/camera.h"
#include "tirpol/acquisition/capture.h"
#include "tirpol/acquisition/capture_session.h"
#include "tirpol/acquisition/ffc.h"
#include "tirpol/acquisition/stage.h"
#include "tirpol/acquisition/stop_on_interrupt.h"
#include "tirpol/core/error.h"
#include "tirpol/core/interrupt_signals.h"

namespace tirpol::cli {

namespace {

/// How long after Ctrl-C the program may take to leave through its clean path before it exits
/// anyway.
constexpr std::chrono::milliseconds kInterruptGrace{1000};

struct AcquireArgs {
    std::string plan, camera, stage, blackbody, output, camera_control, ffc;
    bool resume = false, non_interactive = false;
};

bool ask_operator(const std::string& instruction) {
    std::fprintf(stderr, "\n>>> %s, then press Enter (Ctrl-D to stop): ", instruction.c_str());
    std::fflush(stderr);
    std::string line;
    return static_cast<bool>(std::getline(std::cin, line));
}

void run_acquire(const AcquireArgs& a) {
    using namespace acquisition;
    // The session writer refuses a non-empty folder (unless resuming): only the inputs are checked
    // here.
    OutputGuard().input(a.plan, "PLAN").output_session(a.output, "--output").check(false);
    const CapturePlan plan = CapturePlan::load(a.plan);
    const std::filesystem::path dir = a.output;
    if (a.resume && !std::filesystem::exists(dir / kSessionManifestName))
        fail("{}: no session to resume here (no {}); leave out --resume to start one", dir.string(),
             kSessionManifestName);

    // Handlers first, so an interruption at any point after this leaves through the same clean
    // path. First Ctrl-C: the stage is told to stop and the run ends after the current frame. A
    // second one ends the process at once, which is safe too: every session write is atomic.
    const InterruptSignals interrupt;

    // Ctrl-C stops the stage at once (also mid-move or mid-homing) and never waits on a device for
    // more than kInterruptGrace. Declared after `stage` so it stops watching before the stage goes.
    std::unique_ptr<Stage> stage;
    StopOnInterrupt stop_on_interrupt(interrupt.flag(), kInterruptGrace, [dir] {
        std::fprintf(stderr,
                     "\ntirpol acquire: interrupted; a device did not return within %.1f s, "
                     "exiting now. Every step "
                     "recorded so far is kept in %s; run again with --resume to continue\n",
                     std::chrono::duration<double>(kInterruptGrace).count(), dir.c_str());
        std::_Exit(1);
    });
    auto camera = open_camera(a.camera).value_or_throw();
    stage = couple_simulated_polarizer(*camera, open_stage(a.stage).value_or_throw());
    stop_on_interrupt.watch(stage.get());
    const CameraInfo camera_info = camera->info();
    std::unique_ptr<BlackbodyController> blackbody;
    if (!a.blackbody.empty()) blackbody = open_blackbody(a.blackbody).value_or_throw();
    const BlackbodyInfo blackbody_info = blackbody ? blackbody->info() : BlackbodyInfo{};

    SessionWriter session = open_capture_session(dir, camera_info, stage->info(), plan, a.resume,
                                                 blackbody ? &blackbody_info : nullptr);
    if (a.resume) {
        for (const auto& file : session.adopted_files())
            std::fprintf(stderr,
                         "tirpol acquire: recovered %s (written just before the interruption)\n",
                         file.c_str());
    }

    std::unique_ptr<FfcControl> camera_control;
    if (!a.camera_control.empty())
        camera_control = open_ffc_control(a.camera_control).value_or_throw();
    std::optional<FfcOptions> ffc;
    if (!a.ffc.empty() || camera_control)
        ffc = parse_ffc_schedule(a.ffc.empty() ? "every-cycle" : a.ffc);
    if (ffc) ffc->control = camera_control.get();
    if (ffc && a.ffc == "detect" && camera_control)
        fail(
            "--ffc detect watches the frames only; leave out --camera-control, or choose a "
            "schedule for the link");

    CaptureOptions options;
    options.ffc = ffc ? &*ffc : nullptr;
    if (!a.non_interactive) options.prompt = ask_operator;
    options.interrupt = &interrupt.flag();
    options.blackbody = blackbody.get();

    const CaptureSummary s = run_capture(*camera, *stage, plan, session, options);
    std::printf("session complete: %s\n", dir.c_str());
    std::printf("  steps: %zu (%zu recorded now, %zu were already there)\n", s.steps_total,
                s.steps_recorded, s.steps_already_recorded);
    std::printf("  frames averaged now: %llu, dropped by the camera: %llu\n",
                static_cast<unsigned long long>(s.frames),
                static_cast<unsigned long long>(s.dropped));
    if (ffc)
        std::printf(
            "  flat-field corrections: %d scheduled between cycles, %d detected inside a cycle "
            "(retaken)\n",
            s.ffc_scheduled, s.ffc_detected);
}

void register_acquire(CLI::App& app) {
    auto args = std::make_shared<AcquireArgs>();
    auto* cmd = app.add_subcommand(
        "acquire", "Run a capture plan: polarizer angles × frames into a session directory");
    cmd->add_option("plan", args->plan, "Capture plan (YAML; docs/acquisition-stages.md)")
        ->required()
        ->check(CLI::ExistingFile);
    cmd->add_option("--camera", args->camera,
                    "Camera URI (aravis://ID, v4l2:///dev/videoN, sim://...)")
        ->required();
    cmd->add_option("--stage", args->stage,
                    "Stage URI (thorlabs-apt:///dev/ttyUSB0, thorlabs-apt+usb://SERIAL, "
                    "elliptec:///dev/ttyUSB0?address=0, sim://)")
        ->required();
    cmd->add_option(
        "--blackbody", args->blackbody,
        "Blackbody controller URI (fluke-4180:///dev/ttyUSB1, fluke-4181://..., sim://): sets the "
        "plan's controlled "
        "blackbody temperatures and waits for stability (docs/acquisition-blackbody.md)");
    cmd->add_option("-o,--output", args->output,
                    "Session directory (new and empty, or an interrupted session with --resume)")
        ->required();
    cmd->add_flag(
        "--resume", args->resume,
        "Continue an interrupted session: skips recorded steps, keeps everything written");
    cmd->add_option(
        "--camera-control", args->camera_control,
        "The camera core's control link (boson:///dev/ttyACM0, or lepton:///dev/video0 with the "
        "camera's telemetry=footer): manual FFC, run between polarizer cycles "
        "(docs/acquisition-cameras.md, FLIR Boson, FLIR Lepton)");
    cmd->add_option(
        "--ffc", args->ffc,
        "Flat-field corrections: detect (no link: find them in the frames, retake the cycle), "
        "every-cycle (default with --camera-control), every:N, fpa:K (when the FPA moved > K "
        "kelvin)");
    cmd->add_flag("--non-interactive", args->non_interactive,
                  "Do not prompt before reference (blackbody/shutter) frames");
    cmd->callback([args] { run_acquire(*args); });
}

}  // namespace

TIRPOL_REGISTER_COMMAND(40, register_acquire);

}  // namespace tirpol::cli
