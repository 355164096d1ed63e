// `tirpol live --camera URI [--stage URI] [--calibration CAL --show radiance|temperature]
// [--port N] [--bind ADDR]`: serves the live view (docs/live.md) until Ctrl-C. Prints the address
// to open.

#include <memory>

#include "cli.h"
#include "common_options.h"
#include "tirpol/live/live_server.h"

namespace tirpol::cli {

namespace {

struct LiveArgs {
    live::LiveViewOptions view;
    live::ServerOptions server;
    std::string show = "counts";
};

void run_live(LiveArgs a) {
    live::check_live_run(a.view, a.server);
    a.view.unit = live::parse_display_unit(a.show);
    live::LiveServer server(a.view, a.server);
    print_text(server.listening_text());
    std::fflush(stdout);
    server.run_until_interrupted();
    print_text("tirpol live: stopped\n");
}

void register_live(CLI::App& app) {
    auto a = std::make_shared<LiveArgs>();
    auto* cmd = app.add_subcommand(
        "live", "Live view in a browser: S0, Stokes with a stage, capture plans from the page");
    cmd->add_option("--camera", a->view.camera_uri,
                    "Camera URI (aravis://ID, v4l2:///dev/videoN, sim://...)")
        ->required();
    cmd->add_option("--stage", a->view.stage_uri,
                    "Stage URI: cycle the polarizer and show S1, S2, DoLP, AoP");
    cmd->add_option("--calibration", a->view.calibration_path,
                    "Radiometric calibration EXR (for --show radiance|temperature)")
        ->check(CLI::ExistingFile);
    cmd->add_option(
           "--show", a->show,
           "What S0 shows: counts, radiance or temperature (the last two need --calibration)")
        ->capture_default_str();
    cmd->add_option("--frames-per-angle", a->view.cycle.frames_per_angle,
                    "Frames averaged per polarizer angle")
        ->capture_default_str();
    cmd->add_option("--settle-s", a->view.cycle.settle_s,
                    "Wait after each move before frames count")
        ->capture_default_str();
    cmd->add_option("--plan", a->view.default_plan,
                    "Capture plan prefilled in the page's capture form");
    cmd->add_option("-o,--output", a->view.default_output,
                    "Session directory prefilled in the page's capture form");
    cmd->add_option("--snapshot-dir", a->view.snapshot_dir,
                    "Folder the page's Snapshot button writes into (EXR + PNG quick looks)");
    cmd->add_flag("--force", a->view.force_snapshots,
                  "Let a snapshot replace an existing file of the same name");
    cmd->add_option("--demosaic", a->view.demosaic,
                    "Microgrid camera without a stage: super-pixel, bilinear or newton (Stokes "
                    "from each frame)")
        ->capture_default_str();
    cmd->add_option("--port", a->server.port,
                    "TCP port 1-65535 (0: pick a free one; the address is printed)")
        ->capture_default_str();
    cmd->add_option("--bind", a->server.bind_address,
                    "Address to listen on; anything but loopback requires the access token in the "
                    "printed URL")
        ->capture_default_str();
    cmd->callback([a] { run_live(*a); });
}

}  // namespace

TIRPOL_REGISTER_COMMAND(45, register_live);

}  // namespace tirpol::cli
