#include "tirpol/acquisition/internal/blackbody_simulator.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "tirpol/core/error.h"
#include "tirpol/core/radiometry.h"

namespace tirpol::acquisition {

namespace fs = fluke_scpi;

std::optional<BlackbodyFault> parse_blackbody_fault(const std::string& text) {
    if (text == "none") return BlackbodyFault::None;
    if (text == "over-temperature") return BlackbodyFault::OverTemperature;
    if (text == "no-reply") return BlackbodyFault::NoReply;
    if (text == "garbled") return BlackbodyFault::Garbled;
    return std::nullopt;
}

namespace {
using Seconds = std::chrono::duration<double>;
}  // namespace

BlackbodySimulator::BlackbodySimulator(BlackbodySimulatorOptions options, Clock::time_point start)
    : m_options(std::move(options)),
      m_rng(m_options.seed),
      m_limit_k(m_options.stability_limit_k),
      m_set_point_k(m_options.ambient_k),
      m_next_sample(start),
      m_from_k(m_options.ambient_k),
      m_target_k(m_options.ambient_k),
      m_since(start) {
    if (m_options.model == "4180") {
        m_min_c = fs::kModel4180MinC;
        m_max_c = fs::kModel4180MaxC;
    } else if (m_options.model == "4181") {
        m_min_c = fs::kModel4181MinC;
        m_max_c = fs::kModel4181MaxC;
    } else {
        fail("blackbody simulator: model '{}': expected 4180 or 4181", m_options.model);
    }
    if (!(m_options.time_constant_s > 0.0) || !(m_options.stability_window_s > 0.0) ||
        !(m_options.sample_period_s > 0.0))
        fail(
            "blackbody simulator: time constant, stability window and sample period must be > 0 s "
            "(got {}, {}, {})",
            m_options.time_constant_s, m_options.stability_window_s, m_options.sample_period_s);
    if (!(m_options.noise_k >= 0.0) || !(m_options.stability_limit_k > 0.0))
        fail("blackbody simulator: noise must be ≥ 0 K and the stability limit > 0 K");
}

double BlackbodySimulator::plate_temperature_k(Clock::time_point now) const {
    std::lock_guard lock(m_mutex);
    const double t = std::max(0.0, Seconds(now - m_since).count());
    return m_target_k + (m_from_k - m_target_k) * std::exp(-t / m_options.time_constant_s);
}

void BlackbodySimulator::set_target_k(double target_k, Clock::time_point now) {
    const double current = plate_temperature_k(now);
    std::lock_guard lock(m_mutex);
    m_from_k = current;
    m_target_k = target_k;
    m_since = now;
}

void BlackbodySimulator::sample_until(Clock::time_point now) {
    // Samples on the device's own clock, however often the host asks: the flag does not depend on
    // polling.
    std::normal_distribution<double> noise(0.0, m_options.noise_k);
    const auto period =
        std::chrono::duration_cast<Clock::duration>(Seconds(m_options.sample_period_s));
    for (; m_next_sample <= now; m_next_sample += period)
        m_samples.push_back({m_next_sample, plate_temperature_k(m_next_sample) +
                                                (m_options.noise_k > 0 ? noise(m_rng) : 0.0)});
    const auto window =
        std::chrono::duration_cast<Clock::duration>(Seconds(m_options.stability_window_s));
    while (m_samples.size() > 1 && m_samples.front().at < now - window - period)
        m_samples.pop_front();
}

bool BlackbodySimulator::stable() const {
    if (m_tripped || m_samples.empty()) return false;
    const auto window =
        std::chrono::duration_cast<Clock::duration>(Seconds(m_options.stability_window_s));
    const auto end = m_samples.back().at;
    if (m_samples.front().at > end - window) return false;  // not a full window of readings yet
    double sum = 0.0, lo = 1e300, hi = -1e300;
    int n = 0;
    for (const auto& s : m_samples) {
        if (s.at < end - window) continue;
        sum += s.reading_k;
        lo = std::min(lo, s.reading_k);
        hi = std::max(hi, s.reading_k);
        ++n;
    }
    const double mean = sum / n;
    return hi - mean <= m_limit_k && mean - lo <= m_limit_k;
}

std::vector<std::uint8_t> BlackbodySimulator::poll(Clock::time_point now) {
    sample_until(now);
    return {};
}

std::vector<std::uint8_t> BlackbodySimulator::receive(std::span<const std::uint8_t> bytes,
                                                      Clock::time_point now) {
    sample_until(now);
    m_rx.insert(m_rx.end(), bytes.begin(), bytes.end());
    std::string out;
    for (;;) {
        const auto end = std::find_if(m_rx.begin(), m_rx.end(),
                                      [](std::uint8_t c) { return c == '\r' || c == '\n'; });
        if (end == m_rx.end()) break;
        const std::string line(m_rx.begin(), end);
        m_rx.erase(m_rx.begin(), end + 1);
        if (line.find_first_not_of(" \t") == std::string::npos)
            continue;  // CR LF: the LF ends an empty command
        std::string reply = execute(line, now);
        if (m_silent || reply.empty()) continue;
        if (m_garbled) {
            // Line noise: bits flipped in every reply, as a failing cable or a wrong baud rate
            // gives.
            for (std::size_t i = 0; i < reply.size(); i += 2)
                reply[i] = static_cast<char>(reply[i] ^ 0x5A);
        }
        out += reply + "\r\n";
    }
    return {out.begin(), out.end()};
}

std::string BlackbodySimulator::execute(const std::string& line, Clock::time_point now) {
    const auto space = line.find_first_of(" \t");
    const std::string header = fs::canonical_header(line.substr(0, space));
    const std::string argument = space == std::string::npos ? "" : line.substr(space + 1);
    auto error = [&](int code, const char* message) {
        m_errors.push_back(fs::format_error({code, message}));
        return std::string();
    };
    auto number_argument = [&]() { return fs::parse_number(argument); };
    const double reading_k =
        m_samples.empty() ? plate_temperature_k(now) : m_samples.back().reading_k;

    if (header == "*IDN?")
        return fmt::format("FLUKE,{},SIM{:05},1.00", m_options.model, m_options.seed % 100000);
    if (header == "*CLS") {
        m_errors.clear();
        return {};
    }
    if (header == "SYST:ERR?") {
        if (m_errors.empty()) return fs::format_error({0, "No error"});
        std::string e = m_errors.front();
        m_errors.pop_front();
        return e;
    }
    if (header == "UNIT:TEMP?") return "C";
    if (header == "UNIT:TEMP") {
        if (argument != "C" && argument != "c")
            return error(-224, "Illegal parameter value");  // °F not simulated
        return {};
    }
    if (header == "SOUR:SENS:DATA?") return fmt::format("{:.3f}", reading_k - kZeroCelsiusK);
    if (header == "SOUR:SPO?") return fmt::format("{:.3f}", m_set_point_k - kZeroCelsiusK);
    if (header == "SOUR:STAB:TEST?") return stable() ? "1" : "0";
    if (header == "SOUR:STAB:LIM?") return fmt::format("{:.3f}", m_limit_k);
    if (header == "SOUR:PROT:TRIP?") return m_tripped ? "1" : "0";
    if (header == "SOUR:STAB:LIM") {
        const auto v = number_argument();
        if (!v) return error(-109, "Missing parameter");
        if (!(*v > 0.0 && *v <= 10.0)) return error(-222, "Data out of range");
        m_limit_k = *v;
        return {};
    }
    if (header == "SOUR:SPO") {
        const auto c = number_argument();
        if (!c) return error(-109, "Missing parameter");
        if (*c < m_min_c || *c > m_max_c) return error(-222, "Data out of range");
        m_set_point_k = *c + kZeroCelsiusK;
        ++m_sets;
        if (m_options.fault != BlackbodyFault::None && m_sets >= m_options.fault_on_set) {
            switch (m_options.fault) {
                case BlackbodyFault::OverTemperature:
                    m_tripped = true;
                    break;
                case BlackbodyFault::NoReply:
                    m_silent = true;
                    break;
                case BlackbodyFault::Garbled:
                    m_garbled = true;
                    break;
                case BlackbodyFault::None:
                    break;
            }
        }
        // A tripped cutout removes heater power: the plate drifts to ambient whatever the
        // set-point.
        set_target_k(m_tripped ? m_options.ambient_k : m_set_point_k, now);
        return {};
    }
    return error(-113, "Undefined header");
}

}  // namespace tirpol::acquisition
