#pragma once
// The steps of `tirpol demo`, in pipeline order. A module adds its step in demo_steps.cpp.

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace tirpol::cli {

struct DemoStep {
    std::string title;
    std::function<void(const std::filesystem::path& out_dir)> run;
};

std::vector<DemoStep> demo_steps();

// Individual steps (one file each).
void demo_radiometry(const std::filesystem::path& out_dir);
void demo_analyzer(const std::filesystem::path& out_dir);

}  // namespace tirpol::cli
