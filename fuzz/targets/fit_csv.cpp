// Fuzz target: measured emissivity CSV for `fit` (fitting::load_emissivity_csv, which validates).
#include "fuzz_support.h"
#include "tirpol/fitting/microfacet_fit.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto path = tirpol::fuzz::write_input("emissivity.csv", data, size);
    tirpol::fuzz::expect_clean_rejection([&] { (void)tirpol::fitting::load_emissivity_csv(path); });
    return 0;
}
