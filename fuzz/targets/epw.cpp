// Fuzz target: EnergyPlus weather files (thermal::load_epw).
#include "fuzz_support.h"
#include "tirpol/thermal/surface_temperature.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto path = tirpol::fuzz::write_input("weather.epw", data, size);
    tirpol::fuzz::expect_clean_rejection([&] { (void)tirpol::thermal::load_epw(path); });
    return 0;
}
