// `tirpol acquire PLAN.yaml --camera URI --stage URI [--blackbody URI] [--camera-control URI]
// [--ffc SCHEDULE] -o DIR [--resume] [--non-interactive]`: runs a capture plan into a session
// directory (docs/acquisition-stages.md, docs/session-format.md). Exit codes: 0 session complete; 1
// an error (bad plan or URI, device fault, interruption — the message says how many steps are
// recorded; continue with --resume); 2 bad command-line usage.

#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include "cli.h"
#include "common_options.h"
#include "tirpol/acquisition/capture.h"

namespace tirpol::cli {

namespace {

struct AcquireArgs {
    acquisition::AcquisitionOptions options;
    std::string plan, output;
    bool non_interactive = false;
};

bool ask_operator(const std::string& instruction) {
    std::fprintf(stderr, "\n>>> %s, then press Enter (Ctrl-D to stop): ", instruction.c_str());
    std::fflush(stderr);
    std::string line;
    return static_cast<bool>(std::getline(std::cin, line));
}

void run_acquire(AcquireArgs& a) {
    a.options.plan = a.plan;
    a.options.session = a.output;
    if (!a.non_interactive) a.options.prompt = ask_operator;
    print_text(acquisition::acquisition_summary_text(acquisition::run_acquisition(a.options)));
}

void register_acquire(CLI::App& app) {
    auto args = std::make_shared<AcquireArgs>();
    auto* cmd = app.add_subcommand(
        "acquire", "Run a capture plan: polarizer angles × frames into a session directory");
    add_required_input(cmd, "plan", args->plan, "Capture plan (YAML; docs/acquisition-stages.md)");
    cmd->add_option("--camera", args->options.camera_uri,
                    "Camera URI (aravis://ID, v4l2:///dev/videoN, sim://...)")
        ->required();
    cmd->add_option("--stage", args->options.stage_uri,
                    "Stage URI (thorlabs-apt:///dev/ttyUSB0, thorlabs-apt+usb://SERIAL, "
                    "elliptec:///dev/ttyUSB0?address=0, sim://)")
        ->required();
    cmd->add_option(
        "--blackbody", args->options.blackbody_uri,
        "Blackbody controller URI (fluke-4180:///dev/ttyUSB1, fluke-4181://..., sim://): sets the "
        "plan's controlled "
        "blackbody temperatures and waits for stability (docs/acquisition-blackbody.md)");
    cmd->add_option("-o,--output", args->output,
                    "Session directory (new and empty, or an interrupted session with --resume)")
        ->required();
    cmd->add_flag(
        "--resume", args->options.resume,
        "Continue an interrupted session: skips recorded steps, keeps everything written");
    cmd->add_option(
        "--camera-control", args->options.camera_control_uri,
        "The camera core's control link (boson:///dev/ttyACM0, or lepton:///dev/video0 with the "
        "camera's telemetry=footer): manual FFC, run between polarizer cycles "
        "(docs/acquisition-cameras.md, FLIR Boson, FLIR Lepton)");
    cmd->add_option(
        "--ffc", args->options.ffc_schedule,
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
