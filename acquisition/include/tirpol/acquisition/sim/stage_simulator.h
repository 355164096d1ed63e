#pragma once
/// \file stage_simulator.h
/// A rotation stage that speaks the real byte protocols (Thorlabs APT binary, Elliptec ASCII) on a
/// pseudo-terminal, with move times from a set speed, injectable faults and the mechanics of a real
/// mount (backlash, lost steps, encoder error; docs/acquisition-stages.md, "Unkind stages"). It is
/// the engine of `tirpol-stage-sim` and runs in-process on a thread in tests; either way the driver
/// under test talks to it through the real serial-port code (termios on the pty's slave side).
///
/// Serving a simulated serial device on a pseudo-terminal: the device is a state machine (bytes in,
/// bytes out, at given times) that the serve loop feeds from the pty's master side, while the
/// driver under test opens the slave side through the real serial-port code (termios). Shared by
/// the stage simulator (`tirpol-stage-sim`) and the blackbody simulator (`tirpol-blackbody-sim`).

#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <optional>
#include <random>
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

enum class SimProtocol { Apt, Elliptec };
enum class SimFault {
    None,
    NoReply,            ///< from the faulty move on, the device answers nothing
    Busy,               ///< APT: the move never completes (moving bits stay set); Elliptec: `GS09`
    Error,              ///< APT: MGMSG_HW_RICHRESPONSE; Elliptec: `GS02` (mechanical time out)
    DisconnectMidMove,  ///< the device hangs up halfway through the move
};
/// Parses "apt" | "elliptec" and "none" | "no-reply" | "busy" | "error" | "disconnect-mid-move".
std::optional<SimProtocol> parse_sim_protocol(const std::string& text);
std::optional<SimFault> parse_sim_fault(const std::string& text);

struct StageSimulatorOptions {
    SimProtocol protocol = SimProtocol::Apt;
    SimFault fault = SimFault::None;
    int fault_on_move = 1;    ///< the 1-based absolute move at which the fault starts
    double deg_per_s = 10.0;  ///< K10CR1 top speed is about 10°/s; ELL14 several hundred °/s
    double start_deg = 37.5;  ///< position at power-up (unknown to the host until homed)
    char elliptec_address = '0';
    std::chrono::milliseconds latency{5};  ///< reply latency of immediate requests
    /// Play between motor and mount: after a reversal the motor turns this far before the mount
    /// follows. The mount sits at the motor's position when it last moved negative (the direction
    /// homing ends in) and `backlash_deg` short of it when it last moved positive.
    double backlash_deg = 0.0;
    /// Chance per absolute move that the motor slips and the mount falls `lost_step_deg` short of
    /// the target (in the direction of the move). The APT step counter still counts the commanded
    /// steps (a K10CR1 has no encoder: the read-back cannot see the loss); the Elliptec reports its
    /// encoder. Homing clears accumulated losses.
    double lost_step_probability = 0.0;
    double lost_step_deg = 0.0;
    std::uint32_t seed = 1;  ///< of the lost-step draws (same seed, same moves: same losses)
    /// Elliptec: amplitude of the encoder's once-per-turn error (read = mount + a·sin(mount)).
    double encoder_error_deg = 0.0;
    /// APT: the home sensor (reported in the status bits as the reverse hardware limit) is active
    /// while the mount is within ± this of the home position.
    double home_sensor_half_width_deg = 0.25;
};

/// The protocol state machine, independent of I/O: bytes in, bytes out, at given times.
class StageSimulator final : public PtyDevice {
public:
    explicit StageSimulator(StageSimulatorOptions options);

    /// Consumes bytes from the host; returns bytes to send back now.
    std::vector<std::uint8_t> receive(std::span<const std::uint8_t> bytes,
                                      Clock::time_point now) override;
    /// Bytes whose time has come (move completions).
    std::vector<std::uint8_t> poll(Clock::time_point now) override;
    /// Whether the device should hang up now (disconnect fault).
    bool hang_up(Clock::time_point now) const override;
    /// Current angle in degrees (interpolated during a move).
    double angle_deg(Clock::time_point now) const;
    /// The mount's physical angle at `now` in degrees [0, 360), turning at deg_per_s during a move;
    /// safe to call from any thread while another serves the protocol (it reads a snapshot of the
    /// trajectory, published at each move start and each poll). What a camera behind the polarizer
    /// sees.
    double physical_angle_deg(Clock::time_point now) const;
    /// Absolute moves that lost steps so far.
    int slipped_moves() const { return m_slipped_moves; }

private:
    std::vector<std::uint8_t> receive_apt(Clock::time_point now);
    std::vector<std::uint8_t> receive_elliptec(Clock::time_point now);
    /// Starts a move to `target_deg`; returns whether the fault fires on this move.
    bool start_move(double target_deg, bool homing, Clock::time_point now);
    /// Ends any motion where the stage is now (APT MOVE_STOP, Elliptec `st`); drops the pending
    /// completion message. A homing cut short leaves the stage not homed.
    void stop_motion(Clock::time_point now);
    bool moving(Clock::time_point now) const;
    /// The mount (after backlash and lost steps) at `now`, unwrapped.
    double mount_deg(Clock::time_point now) const;
    /// What the Elliptec's encoder reads with the mount at `mount_deg`.
    double encoder_deg(double mount_deg) const;
    bool home_sensor_active(Clock::time_point now) const;

    StageSimulatorOptions m_options;
    std::vector<std::uint8_t> m_rx;
    double m_from_deg, m_to_deg;  ///< the step counter's positions (what an APT reports)
    double m_mount_from_deg, m_mount_to_deg;  ///< where the mount really is
    double m_slip_deg = 0.0;                  ///< counter − motor shaft: steps lost since homing
    int m_slipped_moves = 0;
    std::mt19937 m_random;
    Clock::time_point m_move_start{}, m_move_end{};
    bool m_homing = false, m_homed = false, m_silent = false, m_stuck = false;
    std::optional<Clock::time_point> m_hang_up_at;
    int m_moves = 0;
    struct Pending {
        Clock::time_point due;
        std::vector<std::uint8_t> bytes;
    };
    std::vector<Pending> m_pending;

    /// The trajectory as other threads see it (physical_angle_deg).
    struct Trajectory {
        double from_deg = 0.0, to_deg = 0.0;
        Clock::time_point start{}, end{};
        bool stuck = false;
    };
    void publish_trajectory();
    mutable std::mutex m_trajectory_mutex;
    Trajectory m_trajectory;
};

/// Serves `simulator` on `pty` until `stop` is set or the simulator hangs up (serve_pty_device).
void serve_stage_simulator(StageSimulator& simulator, PseudoTerminal& pty,
                           const std::atomic<bool>& stop);

}  // namespace tirpol::acquisition
