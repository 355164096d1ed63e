#pragma once
// The steps of `tirpol demo`, in pipeline order. Each step lives in its own demo_*.cpp file and
// registers itself with TIRPOL_REGISTER_DEMO_STEP(order, "title", function); `order` is the
// position in the pipeline (radiometry 100, materials 200, simulation 300, acquisition 400,
// calibration 500, fitting 600, report 700).

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "cli.h"

namespace tirpol::cli {

struct DemoStep {
    int order;
    std::string title;
    std::function<void(const std::filesystem::path& out_dir)> run;
};

bool register_demo_step(DemoStep step);
/// Registered steps sorted by order.
std::vector<DemoStep> demo_steps();

}  // namespace tirpol::cli

#define TIRPOL_REGISTER_DEMO_STEP(order, title, function)                \
    static const bool TIRPOL_CONCAT(tirpol_demo_registered_, __LINE__) = \
        ::tirpol::cli::register_demo_step({order, title, function})
