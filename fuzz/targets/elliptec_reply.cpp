// Fuzz target: Elliptec reply decoding, as the stage driver consumes a serial stream: split CR LF
// lines, parse each reply and its IN / GS / PO payloads.
#include <string>

#include "fuzz_support.h"
#include "tirpol/acquisition/internal/elliptec_protocol.h"

namespace ell = tirpol::acquisition::elliptec;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    std::string buffer(tirpol::fuzz::as_text(data, size));
    while (auto line = ell::take_line(buffer)) {
        const auto reply = ell::parse_reply(*line);
        if (!reply) continue;
        if (const auto info = ell::parse_info(*reply)) (void)info->pulses_per_unit();
        if (const auto code = ell::parse_status(*reply)) (void)ell::status_meaning(*code);
        (void)ell::decode_position(reply->data);
    }
    return 0;
}
