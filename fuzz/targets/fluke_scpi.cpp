// Fuzz target: the Fluke 4180/4181 blackbody's serial replies (acquisition/fluke_scpi.h), line by
// line as the driver reads them (LF-terminated, a CR before it dropped), through every reply
// parser; and each line as a command header, as the simulator canonicalises what the driver sends.
// Invariants: a parsed number is finite, an error entry survives format_error → parse_error
// unchanged.
#include "tirpol/acquisition/internal/fluke_scpi.h"

#include <cmath>
#include <string>

#include "fuzz_support.h"

namespace fs = tirpol::acquisition::fluke_scpi;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    std::string_view rest = tirpol::fuzz::as_text(data, size);
    while (!rest.empty()) {
        const auto lf = rest.find('\n');
        std::string_view line = rest.substr(0, lf);
        rest.remove_prefix(lf == std::string_view::npos ? rest.size() : lf + 1);
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);

        if (const auto v = fs::parse_number(line); v && !std::isfinite(*v)) __builtin_trap();
        (void)fs::parse_flag(line);
        if (const auto e = fs::parse_error(line)) {
            const auto again = fs::parse_error(fs::format_error(*e));
            if (!again || again->code != e->code || again->message != e->message) __builtin_trap();
        }
        (void)fs::parse_identity(line);
        (void)fs::canonical_header(line);
    }
    return 0;
}
