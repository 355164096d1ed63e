#pragma once
// The stage simulator engine on a thread, serving a fresh pseudo-terminal that a driver opens
// through the real serial-port code.

#include <atomic>
#include <string>
#include <thread>

#include "tirpol/acquisition/sim/stage_simulator.h"

namespace tirpol::test {

class StageSimulatorThread {
public:
    explicit StageSimulatorThread(acquisition::StageSimulatorOptions options)
        : m_simulator(options),
          m_pty(acquisition::PseudoTerminal::open().value_or_throw()),
          m_path(m_pty.slave_path()) {
        m_thread = std::thread([this] { serve_stage_simulator(m_simulator, m_pty, m_stop); });
    }
    ~StageSimulatorThread() {
        m_stop = true;
        m_thread.join();
    }
    StageSimulatorThread(const StageSimulatorThread&) = delete;
    StageSimulatorThread& operator=(const StageSimulatorThread&) = delete;
    const std::string& path() const { return m_path; }
    /// The engine, for what tests observe from outside the protocol (physical_angle_deg, which is
    /// safe to call while the thread serves).
    const acquisition::StageSimulator& simulator() const { return m_simulator; }

private:
    acquisition::StageSimulator m_simulator;
    acquisition::PseudoTerminal m_pty;
    std::string m_path;
    std::atomic<bool> m_stop{false};
    std::thread m_thread;
};

}  // namespace tirpol::test
