// Fuzz target: a session directory's manifest (read_session on session.json). Frame files are
// absent, so a manifest that lists any must be rejected cleanly.
#include "fuzz_support.h"
#include "tirpol/core/session.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto path = tirpol::fuzz::write_input("session/session.json", data, size);
    tirpol::fuzz::expect_clean_rejection([&] { (void)tirpol::read_session(path.parent_path()); });
    return 0;
}
