// `tirpol sweep SWEEP.yaml -o OUT [--resume] [--threads N]`: renders every point of a sweep (time
// of day, materials, camera, band, sensor NEDT) with its statistics, plots, contact sheets and, for
// a time-of-day sweep, an animation (docs/sweep.md). Under `mpirun -np N` the points are spread
// over the ranks.

#include "cli.h"
#include "common_options.h"
#include "tirpol/core/error.h"
#include "tirpol/sweep/sweep_run.h"

namespace tirpol::cli {

namespace {
struct SweepArgs {
    std::string sweep_file;
    std::string out_dir;
    int threads = 0;
    bool resume = false;
    bool quiet = false;
    bool force = false;
};

void run_sweep_command(const SweepArgs& a) {
    const sweep::SweepSpec spec = sweep::load_sweep(a.sweep_file);
    OutputGuard()
        .input(a.sweep_file, "SWEEP")
        .output_folder(a.out_dir, "--output", sweep::sweep_output_patterns())
        .check(a.force);
    const sweep::SweepSummary summary =
        sweep::run_sweep(spec, a.out_dir, {a.threads, a.resume, !a.quiet});
    if (!summary.is_root) return;
    print_text(sweep::sweep_summary_text(summary, a.sweep_file, a.out_dir));
    if (summary.failed > 0)
        fail("{} of {} points failed (listed above and in {}/manifest.json)", summary.failed,
             summary.points.size(), a.out_dir);
}

void register_sweep(CLI::App& app) {
    auto args = std::make_shared<SweepArgs>();
    auto* cmd = app.add_subcommand(
        "sweep", "Render a sweep of a scene over time of day, materials, camera, band, NEDT");
    add_required_input(cmd, "sweep", args->sweep_file, "Sweep YAML (docs/sweep.md)");
    cmd->add_option("-o,--output", args->out_dir, "Output folder (points/, manifest.json, results)")
        ->required();
    cmd->add_option("--threads", args->threads,
                    "Renderer threads per rank (default: cores / ranks on this machine); images do "
                    "not depend on it");
    cmd->add_flag("--resume", args->resume,
                  "Continue the sweep in the output folder; finished points are kept");
    cmd->add_flag("-q,--quiet", args->quiet, "No line per finished point");
    add_force_flag(cmd, args->force);
    cmd->callback([args] { run_sweep_command(*args); });
}
}  // namespace

TIRPOL_REGISTER_COMMAND(330, register_sweep);

}  // namespace tirpol::cli
