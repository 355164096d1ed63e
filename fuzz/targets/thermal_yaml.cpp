// Fuzz target: standalone thermal YAML (thermal::load_thermal_scene).
#include "fuzz_support.h"
#include "tirpol/thermal/thermal_config.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto path = tirpol::fuzz::write_input("thermal.yaml", data, size);
    tirpol::fuzz::expect_clean_rejection([&] { (void)tirpol::thermal::load_thermal_scene(path); });
    return 0;
}
