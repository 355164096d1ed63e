// Fuzz target: scene YAML (simulation::load_scene), including the mesh, material and temperature
// descriptions it parses inline. Referenced files are absent, which must give a clean error.
#include "fuzz_support.h"
#include "tirpol/simulation/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto path = tirpol::fuzz::write_input("scene.yaml", data, size);
    tirpol::fuzz::expect_clean_rejection([&] { (void)tirpol::simulation::load_scene(path); });
    return 0;
}
