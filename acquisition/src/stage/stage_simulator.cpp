#include "tirpol/acquisition/sim/stage_simulator.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>

#include "tirpol/acquisition/internal/angles.h"
#include "tirpol/acquisition/internal/apt_protocol.h"
#include "tirpol/acquisition/internal/elliptec_protocol.h"

namespace tirpol::acquisition {

std::optional<SimProtocol> parse_sim_protocol(const std::string& text) {
    if (text == "apt") return SimProtocol::Apt;
    if (text == "elliptec") return SimProtocol::Elliptec;
    return std::nullopt;
}

std::optional<SimFault> parse_sim_fault(const std::string& text) {
    if (text == "none") return SimFault::None;
    if (text == "no-reply") return SimFault::NoReply;
    if (text == "busy") return SimFault::Busy;
    if (text == "error") return SimFault::Error;
    if (text == "disconnect-mid-move") return SimFault::DisconnectMidMove;
    return std::nullopt;
}

namespace {
constexpr double kAptCountsPerDegree = apt::kK10cr1CountsPerDegree;
// An ELL14 reports 143360 pulses (0x23000) over its 360° travel in its IN reply.
constexpr std::uint32_t kEll14Pulses = 0x23000;
constexpr double kEllPulsesPerDegree = kEll14Pulses / 360.0;

std::vector<std::uint8_t> bytes_of(const std::string& s) { return {s.begin(), s.end()}; }
}  // namespace

StageSimulator::StageSimulator(StageSimulatorOptions options)
    : m_options(options),
      m_from_deg(wrap_degrees(options.start_deg)),
      m_to_deg(m_from_deg),
      m_mount_from_deg(m_from_deg),
      m_mount_to_deg(m_from_deg),
      m_random(options.seed) {
    publish_trajectory();
}

void StageSimulator::publish_trajectory() {
    std::lock_guard lock(m_trajectory_mutex);
    m_trajectory = {m_mount_from_deg, m_mount_to_deg, m_move_start, m_move_end, m_stuck};
}

double StageSimulator::mount_deg(Clock::time_point now) const {
    if (!moving(now)) return m_mount_to_deg;
    const double total = std::chrono::duration<double>(m_move_end - m_move_start).count();
    double f = total > 0 ? std::chrono::duration<double>(now - m_move_start).count() / total : 1.0;
    if (m_stuck) f = 0.5;
    return m_mount_from_deg + (m_mount_to_deg - m_mount_from_deg) * std::clamp(f, 0.0, 1.0);
}

double StageSimulator::encoder_deg(double mount) const {
    constexpr double kRadPerDeg = 3.14159265358979323846 / 180.0;
    return mount + m_options.encoder_error_deg * std::sin(mount * kRadPerDeg);
}

bool StageSimulator::home_sensor_active(Clock::time_point now) const {
    return std::abs(angle_difference_deg(wrap_degrees(mount_deg(now)), 0.0)) <=
           m_options.home_sensor_half_width_deg;
}

double StageSimulator::physical_angle_deg(Clock::time_point now) const {
    std::lock_guard lock(m_trajectory_mutex);
    const Trajectory& t = m_trajectory;
    if (!t.stuck && now >= t.end) return wrap_degrees(t.to_deg);
    const double total = std::chrono::duration<double>(t.end - t.start).count();
    double f = total > 0 ? std::chrono::duration<double>(now - t.start).count() / total : 1.0;
    if (t.stuck) f = 0.5;  // as angle_deg(): a busy stage that never arrives sits halfway
    return wrap_degrees(t.from_deg + (t.to_deg - t.from_deg) * std::clamp(f, 0.0, 1.0));
}

bool StageSimulator::moving(Clock::time_point now) const { return m_stuck || now < m_move_end; }

double StageSimulator::angle_deg(Clock::time_point now) const {
    if (!moving(now)) return m_to_deg;
    const double total = std::chrono::duration<double>(m_move_end - m_move_start).count();
    double f = total > 0 ? std::chrono::duration<double>(now - m_move_start).count() / total : 1.0;
    if (m_stuck) f = 0.5;  // a busy stage that never arrives sits halfway
    return m_from_deg + (m_to_deg - m_from_deg) * std::clamp(f, 0.0, 1.0);
}

bool StageSimulator::hang_up(Clock::time_point now) const {
    return m_hang_up_at && now >= *m_hang_up_at;
}

bool StageSimulator::start_move(double target_deg, bool homing, Clock::time_point now) {
    m_mount_from_deg = mount_deg(now);
    m_from_deg = angle_deg(now);
    m_to_deg = target_deg;
    m_homing = homing;
    if (homing) {
        // Homing ends at the home switch, arriving in the negative direction: the counter is
        // zeroed there, the losses are gone and the play is taken up on the negative side.
        m_slip_deg = 0.0;
        m_mount_to_deg = 0.0;
    } else {
        const double delta = m_to_deg - m_from_deg;
        if (m_options.lost_step_probability > 0 && delta != 0.0 &&
            std::uniform_real_distribution<double>(0.0, 1.0)(m_random) <
                m_options.lost_step_probability) {
            m_slip_deg += std::copysign(std::min(m_options.lost_step_deg, std::abs(delta)), delta);
            ++m_slipped_moves;
        }
        // The mount follows the shaft (counter − losses) only once the play is taken up.
        const double shaft_to = m_to_deg - m_slip_deg;
        m_mount_to_deg = delta > 0   ? std::max(m_mount_from_deg, shaft_to - m_options.backlash_deg)
                         : delta < 0 ? std::min(m_mount_from_deg, shaft_to)
                                     : m_mount_from_deg;
    }
    const double seconds = std::abs(m_to_deg - m_from_deg) / m_options.deg_per_s;
    m_move_start = now;
    m_move_end =
        now + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds)) +
        m_options.latency;
    publish_trajectory();
    if (homing) return false;
    ++m_moves;
    return m_options.fault != SimFault::None && m_moves >= m_options.fault_on_move;
}

void StageSimulator::stop_motion(Clock::time_point now) {
    m_mount_from_deg = m_mount_to_deg = mount_deg(now);
    m_from_deg = m_to_deg = angle_deg(now);
    m_move_end = now;
    m_homing = m_stuck = false;
    m_pending.clear();  // only move completions wait there
}

std::vector<std::uint8_t> StageSimulator::receive(std::span<const std::uint8_t> bytes,
                                                  Clock::time_point now) {
    m_rx.insert(m_rx.end(), bytes.begin(), bytes.end());
    if (m_silent) {
        m_rx.clear();
        return {};
    }
    return m_options.protocol == SimProtocol::Apt ? receive_apt(now) : receive_elliptec(now);
}

std::vector<std::uint8_t> StageSimulator::poll(Clock::time_point now) {
    std::vector<std::uint8_t> out;
    auto due = std::stable_partition(m_pending.begin(), m_pending.end(),
                                     [&](const Pending& p) { return p.due > now; });
    for (auto it = due; it != m_pending.end(); ++it)
        out.insert(out.end(), it->bytes.begin(), it->bytes.end());
    m_pending.erase(due, m_pending.end());
    if (!moving(now) && m_homing) {
        m_homing = false;
        m_homed = true;
    }
    publish_trajectory();  // fault handling may have changed the trajectory after start_move
    return out;
}

std::vector<std::uint8_t> StageSimulator::receive_apt(Clock::time_point now) {
    std::vector<std::uint8_t> out;
    auto append = [&out](const std::vector<std::uint8_t>& b) {
        out.insert(out.end(), b.begin(), b.end());
    };
    auto status_now = [&](std::uint16_t id, double angle) {
        apt::StatusUpdate s;
        s.position = static_cast<std::int32_t>(std::llround(angle * kAptCountsPerDegree));
        s.status_bits = apt::kChannelEnabled | (m_homed ? apt::kHomed : 0u) |
                        (home_sensor_active(now) ? apt::kCcwHardLimit : 0u);
        if (moving(now))
            s.status_bits |= m_homing ? apt::kHoming
                                      : (m_to_deg >= m_from_deg ? apt::kMovingCw : apt::kMovingCcw);
        return apt::status_message(id, s);
    };
    for (;;) {
        // As a controller does: bytes that do not start a header from the host (an Elliptec probe,
        // line noise) are dropped one at a time until a valid header lines up again.
        const auto d = apt::decode_host_request(m_rx);
        if (d.status == apt::DecodeStatus::NeedMore) break;
        m_rx.erase(m_rx.begin(), m_rx.begin() + static_cast<std::ptrdiff_t>(d.consumed));
        if (d.status == apt::DecodeStatus::Invalid) continue;
        const apt::Message& m = d.message;
        switch (m.id) {
            case apt::kHwReqInfo: {
                apt::HardwareInfo info;
                info.serial = 55000123;
                info.model = "K10CR1";
                info.type = 16;
                info.firmware_major = 3;
                info.firmware_interim = 0;
                info.firmware_minor = 10;
                info.notes = "tirpol-stage-sim K10CR1";
                info.channels = 1;
                append(apt::hw_get_info(info));
                break;
            }
            case apt::kMotReqUStatusUpdate:
                append(status_now(apt::kMotGetUStatusUpdate, angle_deg(now)));
                break;
            case apt::kMotMoveHome:
                start_move(0.0, true, now);
                m_pending.push_back(
                    {m_move_end, apt::encode_short(apt::kMotMoveHomed, 1, 0, apt::kHostAddress,
                                                   apt::kUsbDeviceAddress)});
                break;
            case apt::kMotMoveStop: {
                stop_motion(now);
                apt::StatusUpdate s;
                s.position =
                    static_cast<std::int32_t>(std::llround(angle_deg(now) * kAptCountsPerDegree));
                s.status_bits = apt::kChannelEnabled | (m_homed ? apt::kHomed : 0u);
                append(apt::status_message(apt::kMotMoveStopped, s));
                break;
            }
            case apt::kMotMoveAbsolute: {
                if (m.data.size() != 6) break;
                const auto counts = static_cast<std::int32_t>(
                    m.data[2] | (m.data[3] << 8) | (m.data[4] << 16) | (m.data[5] << 24));
                const double target = counts / kAptCountsPerDegree;
                if (!start_move(target, false, now)) {
                    apt::StatusUpdate s;
                    s.position = counts;
                    s.status_bits = apt::kChannelEnabled | apt::kHomed;
                    m_pending.push_back(
                        {m_move_end, apt::status_message(apt::kMotMoveCompleted, s)});
                    break;
                }
                switch (m_options.fault) {
                    case SimFault::NoReply:
                        m_silent = true;
                        break;
                    case SimFault::Busy:
                        m_stuck = true;
                        break;
                    case SimFault::Error:
                        m_to_deg = m_from_deg;
                        m_move_end = now;
                        append(apt::hw_rich_response(
                            {apt::kMotMoveAbsolute, 0x0010,
                             "simulated motion error: position error limit exceeded"}));
                        break;
                    case SimFault::DisconnectMidMove:
                        m_hang_up_at = m_move_start + (m_move_end - m_move_start) / 2;
                        break;
                    case SimFault::None:
                        break;
                }
                break;
            }
            default:
                break;  // NO_FLASH_PROGRAMMING, SET_CHANENABLESTATE, IDENTIFY: no reply
        }
        if (m_silent) break;
    }
    return out;
}

std::vector<std::uint8_t> StageSimulator::receive_elliptec(Clock::time_point now) {
    std::vector<std::uint8_t> out;
    const char a = m_options.elliptec_address;
    auto reply = [&](const std::string& code, const std::string& data) {
        const std::string line = std::string(1, a) + code + data + "\r\n";
        return bytes_of(line);
    };
    auto position = [&](double angle) {
        return elliptec::encode_position(
            static_cast<std::int32_t>(std::llround(wrap_degrees(angle) * kEllPulsesPerDegree)));
    };
    // The ELL14 reports its encoder: where the mount is, with the encoder's own error.
    auto encoder_at = [&](Clock::time_point t) { return encoder_deg(mount_deg(t)); };
    auto append = [&out](const std::vector<std::uint8_t>& b) {
        out.insert(out.end(), b.begin(), b.end());
    };
    for (;;) {
        while (!m_rx.empty() && (m_rx.front() == '\r' || m_rx.front() == '\n'))
            m_rx.erase(m_rx.begin());
        if (m_rx.size() < 3) break;
        const std::string head(m_rx.begin(), m_rx.begin() + 3);
        const std::string cmd = head.substr(1);
        // Not `<address><two lower-case letters>`: garbage or another protocol (APT bytes).
        // Drop one byte and look again, so the next valid command is understood.
        if (!elliptec::valid_address(head[0]) ||
            !std::islower(static_cast<unsigned char>(cmd[0])) ||
            !std::islower(static_cast<unsigned char>(cmd[1]))) {
            m_rx.erase(m_rx.begin());
            continue;
        }
        const std::size_t data_len = cmd == "ma" ? 8 : cmd == "ho" ? 1 : 0;
        if (m_rx.size() < 3 + data_len) break;
        const std::string data(m_rx.begin() + 3,
                               m_rx.begin() + static_cast<std::ptrdiff_t>(3 + data_len));
        m_rx.erase(m_rx.begin(), m_rx.begin() + static_cast<std::ptrdiff_t>(3 + data_len));
        if (head[0] != a) continue;  // addressed to another module
        if (cmd == "in") {
            elliptec::DeviceInfo info;
            info.motor_type = 14;
            info.serial = "11400123";
            info.year = "2023";
            info.firmware = 0x17;
            info.hardware_release = 1;
            info.travel = 360;
            info.pulses = kEll14Pulses;
            append(reply("IN", elliptec::encode_info(info)));
        } else if (cmd == "gp") {
            append(reply("PO", position(encoder_at(now))));
        } else if (cmd == "st") {
            stop_motion(now);
            append(reply("GS", "00"));
        } else if (cmd == "gs") {
            append(reply("GS", moving(now) ? "09" : "00"));
        } else if (cmd == "ho") {
            if (moving(now)) {
                append(reply("GS", "09"));
                continue;
            }
            start_move(0.0, true, now);
            m_pending.push_back({m_move_end, reply("PO", position(encoder_deg(0.0)))});
        } else if (cmd == "ma") {
            const auto pulses = elliptec::decode_position(data);
            if (!pulses) {
                append(reply("GS", "03"));
                continue;
            }
            if (moving(now)) {
                append(reply("GS", "09"));
                continue;
            }
            const double target = *pulses / kEllPulsesPerDegree;
            if (!start_move(target, false, now)) {
                m_pending.push_back({m_move_end, reply("PO", position(encoder_at(m_move_end)))});
                continue;
            }
            switch (m_options.fault) {
                case SimFault::NoReply:
                    m_silent = true;
                    break;
                case SimFault::Busy:
                    m_move_end = now;
                    m_to_deg = m_from_deg;
                    m_moves = m_options.fault_on_move - 1;  // every retry is the faulty move again
                    append(reply("GS", "09"));
                    break;
                case SimFault::Error:
                    m_move_end = now;
                    m_to_deg = m_from_deg;
                    append(reply("GS", fmt::format("{:02X}", static_cast<int>(
                                                                 elliptec::kMechanicalTimeout))));
                    break;
                case SimFault::DisconnectMidMove:
                    m_hang_up_at = m_move_start + (m_move_end - m_move_start) / 2;
                    break;
                case SimFault::None:
                    break;
            }
        } else {
            append(reply("GS", "03"));  // command error or not supported
        }
        if (m_silent) break;
    }
    return out;
}

void serve_stage_simulator(StageSimulator& simulator, PseudoTerminal& pty,
                           const std::atomic<bool>& stop) {
    serve_pty_device(simulator, pty, stop);
}

}  // namespace tirpol::acquisition
