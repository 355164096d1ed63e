// Fuzz target: capture plan YAML (acquisition::CapturePlan::parse) and its expansion into steps.
#include "tirpol/acquisition/capture_plan.h"

#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    tirpol::fuzz::expect_clean_rejection([&] {
        const auto plan = tirpol::acquisition::CapturePlan::parse(
            tirpol::ConfigNode::parse(tirpol::fuzz::as_text(data, size), "plan.yaml"));
        (void)tirpol::acquisition::plan_steps(plan);
        (void)plan.to_json().dump();
    });
    return 0;
}
