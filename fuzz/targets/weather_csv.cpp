// Fuzz target: field-log weather CSV (thermal::load_weather_csv), for a site at UTC−7 so that times
// without an offset take the site's standard time (docs/thermal.md).
#include "fuzz_support.h"
#include "tirpol/thermal/surface_temperature.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto path = tirpol::fuzz::write_input("weather.csv", data, size);
    const tirpol::thermal::Site site{"fuzz", 40.0, -111.0, -7.0, 1400.0};
    tirpol::fuzz::expect_clean_rejection(
        [&] { (void)tirpol::thermal::load_weather_csv(path, site); });
    return 0;
}
