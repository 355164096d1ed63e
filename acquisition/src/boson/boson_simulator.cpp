#include "tirpol/acquisition/internal/boson_simulator.h"

#include <cmath>

namespace tirpol::acquisition {

using namespace boson;

namespace {
constexpr double kZeroCelsiusK = 273.15;

Reply ok_reply(const Command& c) { return Reply{c.sequence, c.function, kSuccess, {}}; }
Reply error_reply(const Command& c, std::uint32_t code) {
    return Reply{c.sequence, c.function, code, {}};
}
Reply u32_reply(const Command& c, std::uint32_t value) {
    Reply r = ok_reply(c);
    append_u32(r.data, value);
    return r;
}
Reply u16_reply(const Command& c, std::uint16_t value) {
    Reply r = ok_reply(c);
    append_u16(r.data, value);
    return r;
}
}  // namespace

BosonSimulator::BosonSimulator(std::shared_ptr<BosonCoreModel> core, BosonSimulatorOptions options)
    : m_core(std::move(core)), m_options(options) {}

Reply BosonSimulator::answer(const Command& c, Clock::time_point now) {
    BosonCoreModel& core = *m_core;
    // A setter's value must be there and in range, as the core's dispatcher checks.
    auto set_enum = [&](std::int32_t max, auto&& apply) -> Reply {
        if (c.data.size() < 4) return error_reply(c, kCamPackageInsufficientBytes);
        const auto value = static_cast<std::int32_t>(read_u32(c.data, 0));
        if (value < 0 || value > max) return error_reply(c, kCamApiInvalidInput);
        apply(value);
        return ok_reply(c);
    };
    switch (c.function) {
        case kBosonGetCameraSn:
            return u32_reply(c, core.config().serial);
        case kBosonGetCameraPn: {
            Reply r = ok_reply(c);
            r.data.assign(20, 0);
            const std::string& pn = core.config().part_number;
            std::copy(pn.begin(), pn.end(), r.data.begin());
            return r;
        }
        case kBosonLookupFpaTempDegCx10: {
            const double deci_c = std::round((core.fpa_temperature_k(now) - kZeroCelsiusK) * 10.0);
            return u16_reply(c, static_cast<std::uint16_t>(static_cast<std::int16_t>(deci_c)));
        }
        case kBosonGetFfcMode:
            return u32_reply(c, static_cast<std::uint32_t>(core.ffc_mode()));
        case kBosonSetFfcMode:
            return set_enum(static_cast<std::int32_t>(FfcMode::ShutterTest),
                            [&](std::int32_t v) { core.set_ffc_mode(static_cast<FfcMode>(v)); });
        case kBosonGetGainMode:
            return u32_reply(c, static_cast<std::uint32_t>(core.gain_mode()));
        case kBosonSetGainMode:
            return set_enum(static_cast<std::int32_t>(GainMode::Manual),
                            [&](std::int32_t v) { core.set_gain_mode(static_cast<GainMode>(v)); });
        case kBosonRunFfc:
            core.run_ffc(now);
            return ok_reply(c);
        case kBosonGetFfcStatus:
            return u32_reply(c, static_cast<std::uint32_t>(core.ffc_status(now)));
        case kBosonGetFfcInProgress:
            return u16_reply(c, core.ffc_in_progress(now) ? 1 : 0);
        case kBosonGetLastFfcFrameCount:
            return u32_reply(c, core.last_ffc_frame_count(now));
        case kRoicGetFrameCount:
            return u32_reply(c, core.frame_count(now));
        case kBosonGetFfcTempThreshold:
            return u16_reply(
                c, static_cast<std::uint16_t>(std::lround(core.ffc_threshold_k() * 10.0)));
        case kBosonSetFfcTempThreshold:
            if (c.data.size() < 2) return error_reply(c, kCamPackageInsufficientBytes);
            core.set_ffc_threshold_k(read_u16(c.data, 0) / 10.0);
            return ok_reply(c);
        default:
            return error_reply(c, kCamDispatchBadCommandId);
    }
}

std::vector<std::uint8_t> BosonSimulator::receive(std::span<const std::uint8_t> bytes,
                                                  Clock::time_point now) {
    for (const DecodedFrame& frame : m_decoder.feed(bytes)) {
        // A damaged command is not answered (the host times out), as the core's frame layer drops
        // it.
        if (frame.status != FrameStatus::Ok || frame.channel != kCommandChannel) continue;
        const auto command = parse_command(frame.payload);
        if (!command) continue;
        ++m_commands;
        const bool faulty =
            m_options.fault != BosonSimFault::None && m_commands == m_options.fault_on_command;
        if (m_options.fault == BosonSimFault::Silent && m_commands >= m_options.fault_on_command)
            continue;
        if (faulty && m_options.fault == BosonSimFault::DropReply) continue;
        Reply reply = answer(*command, now);
        if (faulty && m_options.fault == BosonSimFault::WrongSequence)
            reply.sequence = next_sequence(reply.sequence);
        std::vector<std::uint8_t> out = encode_reply(reply);
        if (faulty && m_options.fault == BosonSimFault::CorruptCrc) {
            // Re-frame with the CRC's low byte flipped (escaping kept valid).
            std::vector<std::uint8_t> payload;
            append_u32(payload, reply.sequence);
            append_u32(payload, reply.function);
            append_u32(payload, reply.status);
            payload.insert(payload.end(), reply.data.begin(), reply.data.end());
            std::vector<std::uint8_t> channel_payload = {kCommandChannel};
            channel_payload.insert(channel_payload.end(), payload.begin(), payload.end());
            const std::uint16_t bad = static_cast<std::uint16_t>(crc16(channel_payload) ^ 0x0001);
            auto push = [&out](std::uint8_t b) {
                if (b != kStartByte && b != kEndByte && b != kEscapeByte) return out.push_back(b);
                out.push_back(kEscapeByte);
                out.push_back(b == kStartByte ? kEscapedStart
                              : b == kEndByte ? kEscapedEnd
                                              : kEscapedEscape);
            };
            out = {kStartByte};
            for (std::uint8_t b : channel_payload) push(b);
            push(static_cast<std::uint8_t>(bad >> 8));
            push(static_cast<std::uint8_t>(bad & 0xFF));
            out.push_back(kEndByte);
        }
        m_pending.push_back({now + m_options.reply_latency, std::move(out)});
    }
    return {};
}

std::vector<std::uint8_t> BosonSimulator::poll(Clock::time_point now) {
    std::vector<std::uint8_t> out;
    while (!m_pending.empty() && m_pending.front().due <= now) {
        out.insert(out.end(), m_pending.front().bytes.begin(), m_pending.front().bytes.end());
        m_pending.pop_front();
    }
    // Keep the device's own clock running (auto FFC) even when the host asks nothing.
    m_core->ffc_in_progress(now);
    return out;
}

}  // namespace tirpol::acquisition
