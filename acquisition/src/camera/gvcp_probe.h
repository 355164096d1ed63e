#pragma once
// A GigE Vision control-channel liveness probe of our own: one READREG command (GVCP, GigE Vision
// 2.0 §15 "GVCP": 0x42 key, flags 0x01 "acknowledge required", command 0x0080, 4 data bytes =
// the register address) on a separate, connected UDP socket. Aravis's own register reads retry
// for 5 × 500 ms and its heartbeat reports a lost camera only after 5 s; this answers in
// milliseconds on a live camera, and a connected socket also hears the ICMP "port unreachable"
// that comes back at once when the process serving the camera is gone. Private to acquisition.

#include <netinet/in.h>

#include <chrono>
#include <cstdint>

namespace tirpol::acquisition::gvcp {

enum class ProbeResult {
    Answered,  ///< a READREG acknowledge came back
    Refused,   ///< ICMP port unreachable: nothing listens on the control port any more
    Silent,    ///< no answer to any try
};

/// GigE Vision bootstrap register "Version" (read-only, readable by any host without privilege).
inline constexpr std::uint32_t kVersionRegister = 0x0000;

/// Reads `register_address` from the device at `device` (its GVCP address and port), `tries`
/// times, waiting `timeout_each` for each acknowledge.
ProbeResult probe_register(const sockaddr_in& device, std::uint32_t register_address,
                           std::chrono::milliseconds timeout_each, int tries);

}  // namespace tirpol::acquisition::gvcp
