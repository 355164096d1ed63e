// Fuzz target: regions-of-interest YAML for `compare` (report::parse_regions).
#include "fuzz_support.h"
#include "tirpol/core/config.h"
#include "tirpol/report/regions.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    tirpol::fuzz::expect_clean_rejection([&] {
        (void)tirpol::report::parse_regions(
            tirpol::ConfigNode::parse(tirpol::fuzz::as_text(data, size), "regions.yaml"));
    });
    return 0;
}
