#pragma once
/// \file pseudo_terminal.h
/// Serving a simulated serial device on a pseudo-terminal: the device is a state machine (bytes in,
/// bytes out, at given times) that the serve loop feeds from the pty's master side, while the
/// driver under test opens the slave side through the real serial-port code (termios). Shared by
/// the stage simulator (`tirpol-stage-sim`) and the blackbody simulator (`tirpol-blackbody-sim`).

#include <atomic>
#include <chrono>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "tirpol/acquisition/result.h"

namespace tirpol::acquisition {

/// A device protocol engine, independent of I/O.
class PtyDevice {
public:
    using Clock = std::chrono::steady_clock;
    virtual ~PtyDevice() = default;
    /// Consumes bytes from the host; returns bytes to send back now.
    virtual std::vector<std::uint8_t> receive(std::span<const std::uint8_t> bytes,
                                              Clock::time_point now) = 0;
    /// Bytes whose time has come (e.g. a move completion); also advances the device's own state.
    virtual std::vector<std::uint8_t> poll(Clock::time_point now) = 0;
    /// Whether the device should hang up now (a disconnect fault).
    virtual bool hang_up(Clock::time_point) const { return false; }
};

/// A pseudo-terminal: the simulator owns the master side; a driver opens `slave_path`.
class PseudoTerminal {
public:
    static Result<PseudoTerminal> open();
    PseudoTerminal(PseudoTerminal&&) noexcept;
    PseudoTerminal& operator=(PseudoTerminal&&) noexcept;
    ~PseudoTerminal();
    int master_fd() const { return m_master; }
    const std::string& slave_path() const { return m_slave_path; }
    /// Closes both sides held here: the driver's next read sees the hang-up.
    void hang_up();

private:
    PseudoTerminal(int master, int slave, std::string path);
    int m_master = -1;
    int m_slave_keepalive =
        -1;  ///< keeps the slave open so the master never reads EIO between clients
    std::string m_slave_path;
};

/// Serves `device` on `pty` until `stop` is set or the device hangs up.
void serve_pty_device(PtyDevice& device, PseudoTerminal& pty, const std::atomic<bool>& stop);

/// The main loop of a simulator program: opens a pseudo-terminal, links `link` to it when not
/// empty, prints the device path on the first line of stdout, serves `device` until SIGINT/SIGTERM
/// and removes the link. Returns the process exit code; `program` prefixes error messages.
int run_pty_simulator_program(PtyDevice& device, const std::string& link, const char* program);

}  // namespace tirpol::acquisition
