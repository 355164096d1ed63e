#pragma once
// MockPureThermalLepton: a MOCK of a Lepton 3.5 behind PureThermal firmware, answering at the
// UVC extension-unit seam (LeptonXu) where the real system has the kernel's UVCIOC_CTRL_QUERY
// ioctl, which cannot run without the board. Shared by the Lepton control and telemetry tests.

#include <algorithm>
#include <cmath>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "tirpol/acquisition/internal/lepton_cci.h"
#include "tirpol/acquisition/internal/lepton_control.h"

namespace tirpol::test {

using acquisition::DeviceError;
using acquisition::DeviceErrorCode;
using acquisition::LeptonXu;
using acquisition::ok_status;
using acquisition::Status;
namespace lepton = acquisition::lepton;

/// A mock Lepton 3.5 behind PureThermal firmware, at the extension-unit seam: it decodes unit and
/// selector back to the CCI command it implements, keeps the attributes, runs FFCs (busy for a few
/// status polls, then the offset of every pixel steps) and writes telemetry row A for each frame.
class MockPureThermalLepton final : public LeptonXu {
public:
    using Bytes = std::vector<std::uint8_t>;
    struct Call {
        std::uint8_t unit, selector;
        bool set;
        Bytes bytes;
    };
    Status get(std::uint8_t unit, std::uint8_t selector, std::span<std::uint8_t> data) override {
        std::lock_guard lock(m_mutex);
        m_calls.push_back({unit, selector, false, {}});
        Bytes value;
        if (is(unit, selector, lepton::kSysFfcShutterMode))
            value = lepton::words_to_bytes(lepton::encode_ffc_shutter_mode(shutter));
        else if (is(unit, selector, lepton::kSysFpaTemperatureKelvin))
            value = lepton::words_to_bytes(
                std::vector<std::uint16_t>{static_cast<std::uint16_t>(std::lround(fpa_k * 100))});
        else if (is(unit, selector, lepton::kSysFfcStatus)) {
            std::uint32_t status = 0;
            if (m_busy_polls_left > 0) {
                status = 1;  // LEP_SYS_STATUS_BUSY
                if (--m_busy_polls_left == 0) finish_ffc();
            }
            if (ffc_fails) status = 0xFFFFFFFFu;  // LEP_SYS_STATUS_ERROR (−1)
            value = lepton::words_to_bytes(lepton::u32_words(status));
        } else if (is(unit, selector, lepton::kRadTLinearEnable))
            value = lepton::words_to_bytes(lepton::u32_words(tlinear_enabled));
        else if (is(unit, selector, lepton::kRadTLinearResolution))
            value = lepton::words_to_bytes(lepton::u32_words(tlinear_resolution));
        else
            return DeviceError{DeviceErrorCode::NotSupported, "mock: no such control"};
        if (value.size() != data.size())
            return DeviceError{DeviceErrorCode::BadReply, "mock: wrong length for the control"};
        std::copy(value.begin(), value.end(), data.begin());
        return ok_status();
    }
    Status set(std::uint8_t unit, std::uint8_t selector,
               std::span<const std::uint8_t> data) override {
        std::lock_guard lock(m_mutex);
        const Bytes bytes(data.begin(), data.end());
        m_calls.push_back({unit, selector, true, bytes});
        const auto words = lepton::bytes_to_words(bytes);
        if (is(unit, selector, lepton::kSysRunFfc) && bytes.size() == 1) {
            start_ffc();
        } else if (is(unit, selector, lepton::kSysFfcShutterMode) && bytes.size() == 32) {
            shutter = *lepton::decode_ffc_shutter_mode(words);
        } else if (is(unit, selector, lepton::kRadTLinearEnable) && bytes.size() == 4) {
            tlinear_enabled = lepton::u32_of(words, 0);
        } else if (is(unit, selector, lepton::kRadTLinearResolution) && bytes.size() == 4) {
            tlinear_resolution = lepton::u32_of(words, 0);
        } else if (is(unit, selector, lepton::kSysTelemetryLocation) && bytes.size() == 4) {
            telemetry_location = lepton::u32_of(words, 0);
        } else if (is(unit, selector, lepton::kSysTelemetryEnable) && bytes.size() == 4) {
            telemetry_enabled = lepton::u32_of(words, 0) != 0;
        } else {
            return DeviceError{DeviceErrorCode::NotSupported, "mock: no such control"};
        }
        return ok_status();
    }
    std::string name() const override { return "mock-purethermal"; }

    /// One frame: the core's offset now, and its telemetry row.
    std::pair<double, std::vector<std::uint16_t>> frame() {
        std::lock_guard lock(m_mutex);
        ++m_frame_counter;
        m_uptime_ms += 37;  // ~27 Hz internal frame rate
        lepton::Telemetry t;
        t.uptime_ms = m_uptime_ms;
        t.status_bits = 3u << 4;  // FFC complete
        t.frame_counter = m_frame_counter;
        t.fpa_temperature_k = fpa_k;
        t.fpa_temperature_at_ffc_k = m_fpa_at_ffc_k;
        t.uptime_at_last_ffc_ms = m_uptime_at_ffc_ms;
        return {m_offset_counts, lepton::encode_telemetry(t)};
    }
    std::vector<Call> calls() {
        std::lock_guard lock(m_mutex);
        return m_calls;
    }
    /// An FFC the core runs on its own (another program on the board, a temperature event).
    void ffc_on_its_own() {
        std::lock_guard lock(m_mutex);
        start_ffc();
        finish_ffc();
    }
    int ffcs() {
        std::lock_guard lock(m_mutex);
        return m_ffcs;
    }

    // The core's attributes (set before use; the mutex guards them while the test runs).
    lepton::FfcShutterMode shutter;
    std::uint32_t tlinear_enabled = 0, tlinear_resolution = 0;
    bool telemetry_enabled = false, ffc_fails = false;
    std::uint32_t telemetry_location = 0;  ///< LEP_TELEMETRY_LOCATION_HEADER, the core's default
    double fpa_k = 305.42;
    int busy_polls = 3;
    double ffc_offset_step_counts = 40.0;

private:
    static bool is(std::uint8_t unit, std::uint8_t selector, std::uint16_t command) {
        return unit == *lepton::xu_unit(command) && selector == lepton::xu_selector(command);
    }
    void start_ffc() { m_busy_polls_left = std::max(busy_polls, 1); }
    void finish_ffc() {
        ++m_ffcs;
        m_busy_polls_left = 0;
        m_uptime_at_ffc_ms = m_uptime_ms;
        m_fpa_at_ffc_k = fpa_k;
        m_offset_counts += m_ffcs % 2 ? ffc_offset_step_counts : -0.5 * ffc_offset_step_counts;
    }

    std::mutex m_mutex;
    std::vector<Call> m_calls;
    int m_busy_polls_left = 0, m_ffcs = 0;
    std::uint32_t m_frame_counter = 1000, m_uptime_ms = 500000, m_uptime_at_ffc_ms = 400000;
    double m_fpa_at_ffc_k = 305.0, m_offset_counts = 0.0;
};

}  // namespace tirpol::test
