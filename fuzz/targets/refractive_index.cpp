// Fuzz target: refractive-index tables (RefractiveIndexTable::load). Each input is read both as a
// refractiveindex.info YAML and as a CSV (the loader chooses by extension), then interpolated.
#include "fuzz_support.h"
#include "tirpol/materials/fresnel.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    for (const char* name : {"index.yml", "index.csv"}) {
        const auto path = tirpol::fuzz::write_input(name, data, size);
        tirpol::fuzz::expect_clean_rejection([&] {
            const auto table = tirpol::materials::RefractiveIndexTable::load(path);
            if (!table.is_constant()) (void)table.at_clamped(10.0);
        });
    }
    return 0;
}
