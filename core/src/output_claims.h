#pragma once
// Between OutputGuard and AtomicFile (private to core): a folder output's ledger (.tirpol-outputs)
// is written just before the first file under that folder, not when the guard's check passes, so a
// command that stops on a bad input after the check leaves nothing behind.

#include <filesystem>

namespace tirpol::detail {

/// Writes the ledger of every checked folder output that `destination` lies under, once each.
void write_output_claims_before(const std::filesystem::path& destination);

}  // namespace tirpol::detail
