#pragma once
/// \file boson_simulator.h
/// The control link of a simulated FLIR Boson: FSLP frames in and out (boson_fslp.h), served on a
/// pseudo-terminal (pseudo_terminal.h) so that the driver under test talks through the real serial
/// code. Each reply leaves a few milliseconds after its command (reply_latency), as the core's do.
/// The state it reports and changes is a BosonCoreModel shared with the simulated video.
/// Faults for tests: drop one reply, corrupt one reply's CRC, answer one command with a wrong
/// sequence number, or go silent from a given command on.

#include <deque>
#include <memory>

#include "tirpol/acquisition/internal/boson_core_model.h"
#include "tirpol/acquisition/internal/boson_fslp.h"
#include "tirpol/acquisition/sim/stage_simulator.h"

namespace tirpol::acquisition {

enum class BosonSimFault {
    None,
    DropReply,      ///< the fault_on_command-th command gets no reply (later ones do)
    CorruptCrc,     ///< ... gets a reply whose CRC is wrong
    WrongSequence,  ///< ... gets a reply carrying sequence + 1
    Silent,         ///< from the fault_on_command-th command on, nothing is answered
};

struct BosonSimulatorOptions {
    std::chrono::microseconds reply_latency{3000};  ///< command received → reply sent
    BosonSimFault fault = BosonSimFault::None;
    int fault_on_command = 1;  ///< 1-based count of commands received
};

class BosonSimulator final : public PtyDevice {
public:
    BosonSimulator(std::shared_ptr<BosonCoreModel> core, BosonSimulatorOptions options = {});
    std::vector<std::uint8_t> receive(std::span<const std::uint8_t> bytes,
                                      Clock::time_point now) override;
    std::vector<std::uint8_t> poll(Clock::time_point now) override;
    const std::shared_ptr<BosonCoreModel>& core() const { return m_core; }

private:
    boson::Reply answer(const boson::Command& command, Clock::time_point now);

    std::shared_ptr<BosonCoreModel> m_core;
    BosonSimulatorOptions m_options;
    boson::FrameDecoder m_decoder;
    int m_commands = 0;
    struct Pending {
        Clock::time_point due;
        std::vector<std::uint8_t> bytes;
    };
    std::deque<Pending> m_pending;
};

}  // namespace tirpol::acquisition
