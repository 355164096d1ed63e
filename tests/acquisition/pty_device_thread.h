#pragma once
// A simulated serial device (a PtyDevice: the blackbody simulator, ...) served on a thread on a
// fresh pseudo-terminal, which a driver opens through the real serial-port code.

#include <atomic>
#include <string>
#include <thread>
#include <utility>

#include "tirpol/acquisition/sim/stage_simulator.h"

namespace tirpol::test {

template <typename Device>
class PtyDeviceThread {
public:
    template <typename... Args>
    explicit PtyDeviceThread(Args&&... args)
        : m_device(std::forward<Args>(args)...),
          m_pty(acquisition::PseudoTerminal::open().value_or_throw()),
          m_path(m_pty.slave_path()) {
        m_thread = std::thread([this] { acquisition::serve_pty_device(m_device, m_pty, m_stop); });
    }
    ~PtyDeviceThread() {
        m_stop = true;
        m_thread.join();
    }
    PtyDeviceThread(const PtyDeviceThread&) = delete;
    PtyDeviceThread& operator=(const PtyDeviceThread&) = delete;
    const std::string& path() const { return m_path; }
    /// For thread-safe observers only (e.g. BlackbodySimulator::plate_temperature_k).
    const Device& device() const { return m_device; }

private:
    Device m_device;
    acquisition::PseudoTerminal m_pty;
    std::string m_path;
    std::atomic<bool> m_stop{false};
    std::thread m_thread;
};

}  // namespace tirpol::test
