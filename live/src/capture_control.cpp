#include "tirpol/live/capture_control.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "tirpol/acquisition/capture.h"
#include "tirpol/acquisition/capture_session.h"
#include "tirpol/acquisition/stop_on_interrupt.h"
#include "tirpol/core/error.h"
#include "tirpol/live/tapped_camera.h"

namespace tirpol::live {

using namespace acquisition;

namespace {
/// After Stop, how long the run may take to end before the log says a device is not returning.
constexpr std::chrono::milliseconds kStopGrace{10000};
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
    const CapturePlan plan = CapturePlan::load(request.plan);
    auto session = std::make_shared<SessionWriter>(
        open_capture_session(request.output, m_feed.camera_info(), m_stage.info(), plan, request.resume));
    m_stop = false;
    m_state = {CapturePhase::Running, plan_steps(plan).size(), session->manifest().records.size(),
               request.output.string(), ""};
    m_thread = std::thread([this, plan, session] {
        if (m_cycle) m_cycle->pause();
        try {
            StopOnInterrupt stopper(m_stop, kStopGrace, [] {
                spdlog::warn("live view: the capture has not ended {} s after Stop; a device is not returning",
                             kStopGrace.count() / 1000);
            });
            stopper.watch(&m_stage);
            TappedCamera camera(m_feed);
            CaptureOptions options;
            options.progress_stream = nullptr;
            options.interrupt = &m_stop;
            const CaptureSummary s = run_capture(camera, m_stage, plan, *session, options);
            finish(CapturePhase::Complete,
                   fmt::format("session complete: {} steps ({} recorded now), {} frames, {} dropped", s.steps_total,
                               s.steps_recorded, s.frames, s.dropped));
        } catch (const Error& e) {
            finish(m_stop ? CapturePhase::Stopped : CapturePhase::Failed, e.what());
        } catch (const std::exception& e) {  // e.g. a full disk (std::filesystem_error): shown, not fatal
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
