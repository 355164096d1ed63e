// Fuzz target: material YAML (materials::load_material).
#include "fuzz_support.h"
#include "tirpol/materials/material.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto path = tirpol::fuzz::write_input("material.yaml", data, size);
    tirpol::fuzz::expect_clean_rejection([&] { (void)tirpol::materials::load_material(path); });
    return 0;
}
