#include <fmt/format.h>

#include <charconv>

#include "tirpol/acquisition/capture.h"
#include "tirpol/acquisition/device_uri.h"
#include "tirpol/acquisition/internal/boson_control.h"
#include "tirpol/acquisition/internal/lepton_control.h"
#include "tirpol/core/error.h"

namespace tirpol::acquisition {

namespace {

/// `lepton:///dev/videoN[?ffc_timeout_ms=3000]`: a Lepton on a PureThermal board, its CCI through
/// the video node's UVC extension units.
Result<std::unique_ptr<FfcControl>> open_lepton_uri(const DeviceUri& u) {
    u.check_keys({"ffc_timeout_ms"});
    if (u.target.empty() || u.target.front() != '/')
        fail(
            "camera control link '{}': expected lepton:///dev/videoN (the PureThermal board's "
            "video node, an absolute path)",
            u.text);
    LeptonControlOptions options;
    const int timeout_ms = u.integer("ffc_timeout_ms", 3000);
    if (timeout_ms < 100 || timeout_ms > 60000)
        fail("camera control link '{}': ffc_timeout_ms = {} (expected 100 to 60000)", u.text,
             timeout_ms);
    options.ffc_timeout = std::chrono::milliseconds(timeout_ms);
    auto xu = open_v4l2_lepton_xu(u.target);
    if (!xu) return xu.error();
    auto control = open_lepton_control(std::move(xu.value()), options);
    if (!control) return control.error();
    return std::unique_ptr<FfcControl>(std::move(control.value()));
}

}  // namespace

Result<std::unique_ptr<FfcControl>> open_ffc_control(const std::string& uri) {
    const DeviceUri u = parse_device_uri(uri);
    if (u.scheme == "lepton") return open_lepton_uri(u);
    if (u.scheme != "boson")
        fail(
            "camera control link '{}': unknown scheme '{}' (expected boson:///dev/ttyACM0 or "
            "lepton:///dev/video0)",
            uri, u.scheme);
    u.check_keys({"timeout_ms"});
    if (u.target.empty())
        fail("camera control link '{}': no serial port (expected boson:///dev/ttyACM0)", uri);
    BosonControlOptions options;
    const int timeout_ms = u.integer("timeout_ms", 500);
    if (timeout_ms < 1 || timeout_ms > 60000)
        fail("camera control link '{}': timeout_ms = {} (expected 1 to 60000)", uri, timeout_ms);
    options.reply_timeout = std::chrono::milliseconds(timeout_ms);
    auto control = open_boson_control(u.target, uri, options);
    if (!control) return control.error();
    return std::unique_ptr<FfcControl>(std::move(control.value()));
}

FfcOptions parse_ffc_schedule(const std::string& text) {
    FfcOptions options;
    auto bad = [&](const char* why) -> FfcOptions {
        fail(
            "--ffc '{}': {} (expected detect, every-cycle, every:N with N ≥ 1, or fpa:K with K > 0 "
            "kelvin)",
            text, why);
    };
    if (text == "detect" || text == "every-cycle") return options;
    const auto colon = text.find(':');
    if (colon == std::string::npos) return bad("unknown schedule");
    const std::string kind = text.substr(0, colon), value = text.substr(colon + 1);
    if (kind == "every") {
        int n = 0;
        const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), n);
        if (ec != std::errc() || end != value.data() + value.size() || n < 1)
            return bad("N is not an integer ≥ 1");
        options.schedule = FfcOptions::Schedule::EveryN;
        options.every_n_cycles = n;
        return options;
    }
    if (kind == "fpa") {
        double k = 0.0;
        const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), k);
        if (ec != std::errc() || end != value.data() + value.size() || !(k > 0.0) || k > 100.0)
            return bad("K is not a number of kelvin in (0, 100]");
        options.schedule = FfcOptions::Schedule::FpaDelta;
        options.fpa_delta_k = k;
        return options;
    }
    return bad("unknown schedule");
}

}  // namespace tirpol::acquisition
