#include "demo_steps.h"

#include <algorithm>

namespace tirpol::cli {

namespace {
std::vector<DemoStep>& registry() {
    static std::vector<DemoStep> steps;
    return steps;
}
}  // namespace

bool register_demo_step(DemoStep step) {
    registry().push_back(std::move(step));
    return true;
}

std::vector<DemoStep> demo_steps() {
    auto steps = registry();
    std::stable_sort(steps.begin(), steps.end(),
                     [](const auto& a, const auto& b) { return a.order < b.order; });
    return steps;
}

}  // namespace tirpol::cli
