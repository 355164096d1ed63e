// `tirpol demo`: runs the examples (examples/, each also its own program tirpol-example-<name>) in
// pipeline order, all writing under one output folder (docs/demo.md).

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "cli.h"
#include "examples.h"

namespace tirpol::cli {

namespace {
void register_demo(CLI::App& app) {
    auto out_dir = std::make_shared<std::string>("demo-output");
    auto force = std::make_shared<bool>(false);
    auto* cmd = app.add_subcommand("demo", "Run the built-in end-to-end demonstration");
    cmd->add_option("-o,--output", *out_dir, "Output folder")->capture_default_str();
    add_force_flag(cmd, *force);
    cmd->callback([out_dir, force] {
        std::vector<std::string> step_folders;
        for (const auto& example : examples::all_examples()) step_folders.push_back(example.name);
        OutputGuard().output_folder(*out_dir, "--output", step_folders).check(*force);
        const std::filesystem::path dir = std::filesystem::absolute(*out_dir);
        std::filesystem::create_directories(dir);
        std::printf("tirpol demo → %s\n", dir.c_str());
        for (const auto& example : examples::all_examples()) {
            std::printf("\n== %s\n", example.title.c_str());
            example.run(dir);
        }
        std::printf("\nDemo finished. Results are in %s\n", dir.c_str());
    });
}

}  // namespace

TIRPOL_REGISTER_COMMAND(1000, register_demo);

}  // namespace tirpol::cli
