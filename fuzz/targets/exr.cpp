// Fuzz target: OpenEXR reading (read_exr), then what `info` does with the result: statistics per
// channel and the header as JSON (strings must come out as valid UTF-8).
#include "fuzz_support.h"
#include "tirpol/core/exr_io.h"
#include "tirpol/core/utf8.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto path = tirpol::fuzz::write_input("image.exr", data, size);
    tirpol::fuzz::expect_clean_rejection([&] {
        const tirpol::Image image = tirpol::read_exr(path);
        for (const auto& name : image.channel_names())
            (void)tirpol::channel_stats(image.channel(name));
        (void)tirpol::json_text(tirpol::attributes_json(image.attributes()));
    });
    return 0;
}
