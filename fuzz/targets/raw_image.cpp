// Fuzz target: raw camera images from other tools (read_raw_image). Each input is read both as a
// PNG and as a TIFF (the reader chooses by extension; OpenCV then sniffs the content).
#include "fuzz_support.h"
#include "tirpol/core/exr_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    for (const char* name : {"raw.png", "raw.tif"}) {
        const auto path = tirpol::fuzz::write_input(name, data, size);
        tirpol::fuzz::expect_clean_rejection([&] { (void)tirpol::read_raw_image(path); });
    }
    return 0;
}
