// Fuzz target: relative spectral response CSV (SpectralResponse::load_csv), then a band integral
// with it, which must be finite for any accepted file.
#include <cmath>
#include <cstdlib>

#include "fuzz_support.h"
#include "tirpol/core/radiometry.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto path = tirpol::fuzz::write_input("rsr.csv", data, size);
    tirpol::fuzz::expect_clean_rejection([&] {
        const auto rsr = tirpol::SpectralResponse::load_csv(path);
        const tirpol::Band band(8.0, 14.0, rsr);
        if (!std::isfinite(band.radiance(300.0))) std::abort();
    });
    return 0;
}
