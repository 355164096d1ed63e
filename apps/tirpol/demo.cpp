// `tirpol demo`: runs what exists of the pipeline end to end on built-in data and writes the
// results under one output folder. Each module extends it (see docs/demo.md).

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "cli.h"
#include "demo_steps.h"

namespace tirpol::cli {

namespace {
void register_demo(CLI::App& app) {
    auto out_dir = std::make_shared<std::string>("demo-output");
    auto force = std::make_shared<bool>(false);
    auto* cmd = app.add_subcommand("demo", "Run the built-in end-to-end demonstration");
    cmd->add_option("-o,--output", *out_dir, "Output folder")->capture_default_str();
    add_force_flag(cmd, *force);
    cmd->callback([out_dir, force] {
        OutputGuard()
            .output_folder(*out_dir, "--output",
                           {"acquisition", "analyzer", "calibration", "fitting", "materials",
                            "radiometry", "simulation", "thermal", "twin"})
            .check(*force);
        const std::filesystem::path dir = std::filesystem::absolute(*out_dir);
        std::filesystem::create_directories(dir);
        std::printf("tirpol demo → %s\n", dir.c_str());
        for (const auto& step : demo_steps()) {
            std::printf("\n== %s\n", step.title.c_str());
            step.run(dir);
        }
        std::printf("\nDemo finished. Results are in %s\n", dir.c_str());
    });
}

}  // namespace

TIRPOL_REGISTER_COMMAND(1000, register_demo);

}  // namespace tirpol::cli
