#include "capture_control.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <filesystem>

#include "tapped_camera.h"
#include "tirpol/acquisition/capture.h"
#include "tirpol/core/error.h"
#include "tirpol/core/utf8.h"

namespace tirpol::live {

using namespace acquisition;

namespace {
/// After Stop, how long the run may take to end before the log says a device is not returning.
constexpr std::chrono::milliseconds kStopGrace{10000};

/// The first string in `json` (a key or a value) that is not valid UTF-8, as a dotted path
/// ("metadata.site"); empty when there is none.
std::string invalid_utf8_field(const nlohmann::json& json, const std::string& path) {
    if (json.is_string()) return is_valid_utf8(json.get_ref<const std::string&>()) ? "" : path;
    if (json.is_object()) {
        for (const auto& [key, value] : json.items()) {
            const std::string field = path + "." + valid_utf8(key);
            if (!is_valid_utf8(key)) return field;
            if (std::string bad = invalid_utf8_field(value, field); !bad.empty()) return bad;
        }
    }
    if (json.is_array()) {
        for (std::size_t i = 0; i < json.size(); ++i)
            if (std::string bad = invalid_utf8_field(json[i], path + "[" + std::to_string(i) + "]");
                !bad.empty())
                return bad;
    }
    return "";
}

/// The plan named by a request from the page. Its own error messages quote the file (a line of it,
/// a key), and the page may have named any file the server can read, so the page is only told that
/// the file is not a capture plan; the reason goes to the terminal running tirpol live.
CapturePlan load_plan_for_page(const std::filesystem::path& path) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        fail("capture plan {}: no such file", path.string());
    CapturePlan plan;
    try {
        plan = CapturePlan::load(path);
    } catch (const Error& e) {
        spdlog::warn("live view: capture plan {} refused: {}", path.string(), e.what());
        // The reader's invalid-UTF-8 error gives a position and a byte value, never a line of the
        // file.
        const std::string message = e.what();
        if (message.rfind(path.string() + ":", 0) == 0 &&
            message.find(": invalid UTF-8 (byte 0x") != std::string::npos)
            fail("capture plan {}", message);
        fail(
            "capture plan {}: not a valid capture plan (the terminal running tirpol live says why; "
            "the page is "
            "never shown a file's contents)",
            path.string());
    }
    // The plan goes into session.json, which must be UTF-8 JSON: name the field instead of failing
    // there.
    if (const std::string field = invalid_utf8_field(plan.metadata, "metadata"); !field.empty())
        fail("capture plan {}: {} is not valid UTF-8 text", path.string(), field);
    return plan;
}
}  // namespace

const char* to_string(CapturePhase phase) {
    switch (phase) {
        case CapturePhase::Idle:
            return "idle";
        case CapturePhase::Running:
            return "running";
        case CapturePhase::Stopping:
            return "stopping";
        case CapturePhase::Complete:
            return "complete";
        case CapturePhase::Stopped:
            return "stopped";
        case CapturePhase::Failed:
            return "failed";
    }
    return "?";
}

CaptureControl::CaptureControl(FrameFeed& feed, Stage& stage, PolarizerCycle* cycle)
    : m_feed(feed), m_stage(stage), m_cycle(cycle) {}

CaptureControl::~CaptureControl() {
    stop();
    if (m_thread.joinable()) m_thread.join();
}

void CaptureControl::start(const CaptureRequest& request) {
    std::lock_guard lock(m_mutex);
    if (m_state.phase == CapturePhase::Running || m_state.phase == CapturePhase::Stopping)
        fail("live view: a capture into {} is running; stop it first", m_state.output);
    if (m_thread.joinable()) m_thread.join();
    const CapturePlan plan = load_plan_for_page(request.plan);
    auto session = std::make_shared<SessionWriter>(open_capture_session(
        request.output, m_feed.camera_info(), m_stage.info(), plan, request.resume));
    m_stop = false;
    m_state = {CapturePhase::Running, plan_steps(plan).size(), session->manifest().records.size(),
               request.output.string(), ""};
    m_thread = std::thread([this, plan, session] {
        if (m_cycle) m_cycle->pause();
        try {
            StopOnInterrupt stopper(m_stop, kStopGrace, [] {
                spdlog::warn(
                    "live view: the capture has not ended {} s after Stop; a device is not "
                    "returning",
                    kStopGrace.count() / 1000);
            });
            stopper.watch(&m_stage);
            TappedCamera camera(m_feed);
            CaptureOptions options;
            options.progress_stream = nullptr;
            options.interrupt = &m_stop;
            const CaptureSummary s = run_capture(camera, m_stage, plan, *session, options);
            finish(
                CapturePhase::Complete,
                fmt::format("session complete: {} steps ({} recorded now), {} frames, {} dropped",
                            s.steps_total, s.steps_recorded, s.frames, s.dropped));
        } catch (const Error& e) {
            finish(m_stop ? CapturePhase::Stopped : CapturePhase::Failed, e.what());
        } catch (const std::exception&
                     e) {  // e.g. a full disk (std::filesystem_error): shown, not fatal
            finish(CapturePhase::Failed, e.what());
        }
        if (m_cycle) m_cycle->resume();
    });
}

void CaptureControl::stop() {
    std::lock_guard lock(m_mutex);
    if (m_state.phase != CapturePhase::Running) return;
    m_state.phase = CapturePhase::Stopping;
    m_stop = true;
}

void CaptureControl::finish(CapturePhase phase, std::string message) {
    std::size_t recorded = 0;
    try {
        recorded = read_session(m_state.output).records.size();
    } catch (const Error&) {
    }
    std::lock_guard lock(m_mutex);
    m_state.phase = phase;
    m_state.steps_recorded = recorded;
    m_state.message = std::move(message);
}

CaptureState CaptureControl::state() const {
    CaptureState s;
    {
        std::lock_guard lock(m_mutex);
        s = m_state;
    }
    if (s.phase == CapturePhase::Running || s.phase == CapturePhase::Stopping) {
        // Progress as the session's own manifest says it (written atomically after each step).
        try {
            s.steps_recorded = read_session(s.output).records.size();
        } catch (const Error&) {
        }
    }
    return s;
}

}  // namespace tirpol::live
