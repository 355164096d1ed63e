// `tirpol therm`: surface temperatures of a thermal model's objects at a time, a CSV of them, and a
// 24-hour plot of every object's surface temperature.

#include "cli.h"
#include "common_options.h"
#include "tirpol/simulation/therm_report.h"

namespace tirpol::cli {

namespace {
void register_therm(CLI::App& app) {
    auto o = std::make_shared<simulation::ThermOptions>();
    auto json = std::make_shared<bool>(false);
    auto* cmd = app.add_subcommand(
        "therm", "Surface temperatures from weather (1D slab model) and a 24-hour plot");
    add_required_input(
        cmd, "file", o->file,
        "Scene YAML with predicted temperatures, or a standalone thermal YAML (docs/thermal.md)");
    cmd->add_option(
        "--at", o->at,
        "Time, ISO 8601 (no offset: the site's standard time); default: the file's `time`");
    cmd->add_option("--csv", o->csv,
                    "Write each object's temperature and surface balance to this CSV");
    cmd->add_option("--plot", o->plot, "Write a 24-hour surface-temperature plot (PNG)");
    cmd->add_option("--export-dir", o->export_dir,
                    "Scene files: write predicted temperatures as <object>.csv (vertex_csv) / "
                    "<object>.exr (texture)");
    add_json_flag(cmd, *json, "Print JSON (keys in docs/thermal.md)");
    add_force_flag(cmd, o->force);
    cmd->callback([o, json] {
        const simulation::ThermReport report = simulation::run_therm(*o);
        *json ? print_json(simulation::therm_report_json(report))
              : print_text(simulation::therm_report_text(report));
    });
}
}  // namespace

TIRPOL_REGISTER_COMMAND(310, register_therm);

}  // namespace tirpol::cli
