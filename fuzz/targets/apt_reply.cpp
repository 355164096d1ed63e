// Fuzz target: Thorlabs APT reply decoding, as the stage driver consumes a byte stream: decode
// messages from the front, resynchronise on Invalid, and parse each known payload.
#include "fuzz_support.h"
#include "tirpol/acquisition/internal/apt_protocol.h"

namespace apt = tirpol::acquisition::apt;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    std::span<const std::uint8_t> rest(data, size);
    while (!rest.empty()) {
        const apt::Decoded d = apt::decode(rest);
        if (d.status == apt::DecodeStatus::NeedMore) break;
        if (d.status == apt::DecodeStatus::Complete) {
            (void)apt::parse_hw_info(d.message);
            (void)apt::parse_status_update(d.message);
            (void)apt::parse_rich_response(d.message);
            (void)apt::message_name(d.message.id);
        }
        // A decoder that consumes nothing would make the driver spin forever.
        if (d.consumed == 0 || d.consumed > rest.size()) __builtin_trap();
        rest = rest.subspan(d.consumed);
    }
    return 0;
}
