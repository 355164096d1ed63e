// Requires TIRPOL_WITH_V4L2 (built only with that back end: cmake/TirpolBackends.cmake).
// A FLIR Lepton's telemetry rows in PureThermal Y16 frames (Lepton IDD 110-0144, "Telemetry";
// PureThermal firmware: footer location; 80×63 for a Lepton 2.x, 160×122 for a Lepton 3.x): split
// off the frame, decoded into Frame::telemetry and the per-frame audit, the image delivered at
// 80×60 / 160×120. The video goes through the real v4l2:// back end over its V4l2Io seam, where
// the kernel is replaced by FakeV4l2Device, a MOCK (no uvcvideo device exists on the build
// machines); the control link's extension units by MockPureThermalLepton, also a MOCK.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>

#include "fake_v4l2_device.h"
#include "mock_purethermal_lepton.h"
#include "test_support.h"
#include "tirpol/acquisition/capture.h"
#include "tirpol/acquisition/internal/lepton_frame.h"
#include "tirpol/acquisition/internal/sim_stage.h"
#include "tirpol/acquisition/internal/v4l2_camera.h"
#include "tirpol/core/error.h"
#include "tirpol/core/session.h"

namespace tirpol::acquisition {
namespace {

using namespace std::chrono_literals;
using test::FakeV4l2Device;
using test::MockPureThermalLepton;
using ::testing::HasSubstr;

/// Image pixel (x, y) of frame `sequence`, distinct per pixel and frame.
std::uint16_t image_word(std::uint32_t x, std::uint32_t y, std::uint32_t sequence) {
    return static_cast<std::uint16_t>((3 * x + 5 * y + 11 * sequence) & 0x3FFF);
}

lepton::Telemetry telemetry_of(std::uint32_t sequence) {
    lepton::Telemetry t;
    t.uptime_ms = 100000 + 37 * sequence;
    t.status_bits = (sequence % 4) << 4;  // every FFC state in turn
    t.frame_counter = 70000 + sequence;   // above 2^16: both words used
    t.fpa_temperature_k = 300.0 + 0.01 * sequence;
    t.uptime_at_last_ffc_ms = 90000;
    return t;
}

/// A PureThermal board streaming `width`×`height` Y16 frames with telemetry rows A, B, C (and the
/// reserved fourth packet of a Lepton 3.x) at `location`.
std::shared_ptr<FakeV4l2Device> purethermal(std::uint32_t width, std::uint32_t height,
                                            LeptonTelemetryLocation location) {
    auto device = std::make_shared<FakeV4l2Device>();
    device->formats = {{V4L2_PIX_FMT_Y16, width, height}};
    const std::uint32_t telemetry_rows = width == 160 ? 2 : 3;
    device->fill_frame = [=](std::uint32_t sequence, std::vector<std::uint16_t>& words) {
        std::vector<std::uint16_t> telemetry = lepton::encode_telemetry(telemetry_of(sequence));
        telemetry.resize(std::size_t{telemetry_rows} * width, 0xBEEF);  // rows B, C, reserved
        const std::uint32_t image_rows = height - telemetry_rows;
        const std::uint32_t first_image_row =
            location == LeptonTelemetryLocation::Header ? telemetry_rows : 0;
        const std::uint32_t first_telemetry_row =
            location == LeptonTelemetryLocation::Header ? 0 : image_rows;
        for (std::uint32_t y = 0; y < image_rows; ++y)
            for (std::uint32_t x = 0; x < width; ++x)
                words[std::size_t{first_image_row + y} * width + x] = image_word(x, y, sequence);
        std::copy(telemetry.begin(), telemetry.end(),
                  words.begin() + static_cast<std::ptrdiff_t>(first_telemetry_row * width));
    };
    return device;
}

std::unique_ptr<Camera> open_lepton(const std::shared_ptr<FakeV4l2Device>& device,
                                    LeptonTelemetryLocation location) {
    V4l2CameraOptions options;
    options.pixel_format = "Y16";
    options.width = static_cast<int>(device->formats.front().width);  // the URI's width=, height=
    options.height = static_cast<int>(device->formats.front().height);
    auto v4l2 = open_v4l2_camera("/dev/video0", options, device).value_or_throw();
    return wrap_lepton_telemetry_camera(std::move(v4l2), location).value_or_throw();
}

void expect_split(const Frame& frame, int width, int height) {
    ASSERT_EQ(frame.width, width);
    ASSERT_EQ(frame.height, height);
    ASSERT_EQ(frame.counts.size(), static_cast<std::size_t>(width * height));
    // The frame's sequence number, from its own telemetry (the fake writes 70000 + sequence).
    const auto sequence = static_cast<std::uint32_t>(frame.telemetry->device_frame_counter - 70000);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            ASSERT_EQ(
                frame.counts[static_cast<std::size_t>(y * width + x)],
                image_word(static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y), sequence))
                << x << "," << y;
    const lepton::Telemetry t = telemetry_of(sequence);
    EXPECT_EQ(frame.telemetry->ffc_state, t.ffc_state());
    EXPECT_EQ(frame.telemetry->uptime_ms, t.uptime_ms);
    EXPECT_EQ(frame.telemetry->uptime_at_last_ffc_ms, t.uptime_at_last_ffc_ms);
    ASSERT_TRUE(frame.fpa_temperature_k);
    EXPECT_NEAR(*frame.fpa_temperature_k, t.fpa_temperature_k, 0.005);  // K × 100 in one word
}

TEST(LeptonTelemetry, Lepton3FooterRowsAreSplitOffAndRowADecoded) {
    auto device = purethermal(160, 122, LeptonTelemetryLocation::Footer);
    auto camera = open_lepton(device, LeptonTelemetryLocation::Footer);
    EXPECT_EQ(camera->info().width, 160);
    EXPECT_EQ(camera->info().height, 120);
    camera->start().value_or_throw();
    std::set<int> states;
    for (int i = 0; i < 6; ++i) {
        const Frame f = camera->grab(1s).value_or_throw();
        ASSERT_TRUE(f.telemetry);
        expect_split(f, 160, 120);
        states.insert(f.telemetry->ffc_state);
    }
    EXPECT_EQ(states.size(), 4u);  // the status bits 4–5 of every state decoded
}

TEST(LeptonTelemetry, Lepton2HeaderRowsAreSplitOffAndRowADecoded) {
    auto device = purethermal(80, 63, LeptonTelemetryLocation::Header);
    auto camera = open_lepton(device, LeptonTelemetryLocation::Header);
    EXPECT_EQ(camera->info().height, 60);
    camera->start().value_or_throw();
    for (int i = 0; i < 3; ++i) {
        const Frame f = camera->grab(1s).value_or_throw();
        ASSERT_TRUE(f.telemetry);
        expect_split(f, 80, 60);
    }
}

TEST(LeptonTelemetry, LayoutsAreTheDocumentedSizesOnly) {
    EXPECT_EQ(lepton_telemetry_layout(160, 122)->telemetry_rows, 2);
    EXPECT_EQ(lepton_telemetry_layout(80, 63)->telemetry_rows, 3);
    EXPECT_FALSE(lepton_telemetry_layout(160, 120));  // telemetry off
    EXPECT_FALSE(lepton_telemetry_layout(160, 123));
    EXPECT_FALSE(lepton_telemetry_layout(640, 514));  // a Boson is not a Lepton
}

TEST(LeptonTelemetry, AFrameWithoutTelemetryRowsOrWithThemElsewhereIsRefusedByName) {
    // Telemetry off: the board streams 160×120; asking for its rows fails when opening.
    auto plain = std::make_shared<FakeV4l2Device>();
    V4l2CameraOptions options;
    options.pixel_format = "Y16";
    auto camera = open_v4l2_camera("/dev/video0", options, plain).value_or_throw();
    auto refused = wrap_lepton_telemetry_camera(std::move(camera), LeptonTelemetryLocation::Footer);
    ASSERT_FALSE(refused);
    EXPECT_EQ(refused.error().code, DeviceErrorCode::NotSupported);
    EXPECT_THAT(refused.error().message, HasSubstr("160×120"));
    EXPECT_THAT(refused.error().message, HasSubstr("160×122"));
    // Rows at the header read as if at the footer: the footer's first word is image data, not a
    // telemetry revision... unless it happens to be nonzero, so make the image's last rows zero.
    auto header = purethermal(160, 122, LeptonTelemetryLocation::Header);
    auto fill = header->fill_frame;
    header->fill_frame = [fill](std::uint32_t sequence, std::vector<std::uint16_t>& words) {
        fill(sequence, words);
        std::fill(words.end() - 2 * 160, words.end(), 0);
    };
    auto wrong = open_lepton(header, LeptonTelemetryLocation::Footer);
    wrong->start().value_or_throw();
    auto bad = wrong->grab(1s);
    ASSERT_FALSE(bad);
    EXPECT_EQ(bad.error().code, DeviceErrorCode::BadReply);
    EXPECT_THAT(bad.error().message, HasSubstr("revision 0"));
    EXPECT_THAT(bad.error().message, HasSubstr("footer"));
}

TEST(LeptonTelemetry, TheV4l2UriTakesTheTelemetryLocationAndRefusesOthers) {
    try {
        (void)open_camera("v4l2:///dev/video0?format=Y16&telemetry=middle");
        FAIL() << "accepted";
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), HasSubstr("telemetry=middle"));
        EXPECT_THAT(e.what(), HasSubstr("footer or header"));
    }
}

// --- the capture: a Lepton 3.x over V4L2 (mock kernel) with its CCI link (mock XU) -------------

constexpr double kSceneCounts = 8000.0;

TEST(LeptonTelemetryCapture, FfcsScheduledThroughTheFramesTelemetryAndEachFrameAudited) {
    // The link hears the core only through the frames the capture grabs: while it waits for an FFC
    // it pulls them itself (FfcControl::set_frame_pull). An FFC the core runs on its own inside
    // cycle 1 moves the telemetry's last-FFC time and the cycle is taken again; the kept records of
    // each cycle share one offset, so S1 = I0 − I90 of the uniform scene stays 0.
    auto xu = std::make_unique<MockPureThermalLepton>();
    MockPureThermalLepton* core = xu.get();
    LeptonControl control(std::move(xu), {2000ms, 1ms});
    auto device = std::make_shared<FakeV4l2Device>();
    device->stamp_with_monotonic_clock = true;
    device->formats = {{V4L2_PIX_FMT_Y16, 160, 122}};
    device->frame_rates_hz = {60};
    device->fill_frame = [core](std::uint32_t, std::vector<std::uint16_t>& words) {
        const auto [offset, row_a] = core->frame();
        std::fill(words.begin(), words.end() - 2 * 160,
                  static_cast<std::uint16_t>(std::lround(kSceneCounts + offset)));
        std::copy(row_a.begin(), row_a.end(), words.end() - 2 * 160);
    };
    V4l2CameraOptions options;
    options.pixel_format = "Y16";
    options.width = 160;
    options.height = 122;
    options.frame_rate_hz = 60.0;
    auto camera = wrap_lepton_telemetry_camera(
                      open_v4l2_camera("/dev/video0", options, device).value_or_throw(),
                      LeptonTelemetryLocation::Footer)
                      .value_or_throw();
    SimulatedStageOptions so;
    so.deg_per_s = 720.0;
    auto stage = make_simulated_stage("sim://", so);
    CapturePlan plan;
    plan.frames_per_angle = 5;
    plan.settle_s = 0.02;
    plan.repeats = 2;
    FfcOptions ffc;
    ffc.control = &control;
    CaptureOptions capture;
    capture.progress_stream = nullptr;
    capture.ffc = &ffc;
    bool provoked = false;
    capture.on_progress = [&](const CaptureProgress& p) {
        if (!provoked && p.event == CaptureProgress::Event::Frame && p.step->repeat == 0 &&
            p.step->angle_deg == 45.0 && p.frames_kept == 2) {
            core->ffc_on_its_own();
            provoked = true;
        }
    };
    test::TempDir tmp;
    auto session =
        SessionWriter::create(tmp / "s", new_session_manifest(camera->info(), stage->info(), plan));
    const auto summary = run_capture(*camera, *stage, plan, session, capture);
    ASSERT_TRUE(provoked);
    EXPECT_EQ(core->shutter.mode, lepton::FfcShutterMode::Manual);
    EXPECT_EQ(summary.ffc_detected, 1);
    EXPECT_EQ(summary.ffc_scheduled, 3);  // before cycles 1 and 2, and before the retake
    EXPECT_EQ(core->ffcs(), 4);

    const SessionManifest m = read_session(tmp / "s");
    EXPECT_EQ(m.schema_version, kSessionSchemaVersion);
    EXPECT_EQ(m.camera.width, 160);
    EXPECT_EQ(m.camera.height, 120);
    ASSERT_EQ(m.records.size(), 8u);
    std::map<int, std::map<double, double>> means;
    std::int64_t last_counter = 0;
    for (const auto& r : m.records) {
        ASSERT_TRUE(r.audit);
        const FrameAudit& a = *r.audit;
        ASSERT_EQ(a.device_frame_counter.size(), 5u);
        ASSERT_EQ(a.ffc_state.size(), 5u);
        for (std::size_t i = 0; i < 5; ++i) {
            ASSERT_TRUE(a.device_frame_counter[i]);
            EXPECT_GT(*a.device_frame_counter[i], last_counter);  // the core's own count, rising
            last_counter = *a.device_frame_counter[i];
            EXPECT_EQ(a.ffc_state[i], 3);  // complete: no frame kept while the shutter moved
            ASSERT_TRUE(a.fpa_temperature_k[i]);
            EXPECT_NEAR(*a.fpa_temperature_k[i], 305.42, 1e-9);
        }
        means[r.repeat][r.angle_deg_requested] =
            read_session_frame(tmp / "s", m, r).channel("counts")[0];
    }
    for (const auto& [repeat, by_angle] : means) {
        EXPECT_EQ(by_angle.at(0.0) - by_angle.at(90.0), 0.0) << "S1 of cycle " << repeat + 1;
        EXPECT_EQ(by_angle.at(45.0) - by_angle.at(135.0), 0.0) << "S2 of cycle " << repeat + 1;
    }
}

// --- lepton:// (tirpol acquire --camera-control)
// --------------------------------------------------

TEST(LeptonControlLink, OpeningChecksALeptonAnswersAndSwitchesItsTelemetryOnAtTheFooter) {
    auto xu = std::make_unique<MockPureThermalLepton>();
    MockPureThermalLepton* core = xu.get();
    auto control = open_lepton_control(std::move(xu)).value_or_throw();
    EXPECT_TRUE(core->telemetry_enabled);
    EXPECT_EQ(core->telemetry_location, 1u);  // LEP_TELEMETRY_LOCATION_FOOTER
    const auto calls = core->calls();
    ASSERT_GE(calls.size(), 3u);
    EXPECT_EQ(calls[1].unit, 6);  // SYS
    EXPECT_EQ(calls[1].selector, 0x1C / 4 + 1);
}

/// Extension units that refuse every control: a UVC camera that is not a PureThermal board.
class NoLeptonXu final : public LeptonXu {
public:
    Status get(std::uint8_t, std::uint8_t, std::span<std::uint8_t>) override {
        return DeviceError{DeviceErrorCode::NotSupported, "UVCIOC_CTRL_QUERY: Invalid argument"};
    }
    Status set(std::uint8_t, std::uint8_t, std::span<const std::uint8_t>) override {
        return DeviceError{DeviceErrorCode::NotSupported, "UVCIOC_CTRL_QUERY: Invalid argument"};
    }
    std::string name() const override { return "/dev/video7"; }
};

TEST(LeptonControlLink, AUvcCameraWithoutALeptonIsRefusedByName) {
    auto refused = open_lepton_control(std::make_unique<NoLeptonXu>());
    ASSERT_FALSE(refused);
    EXPECT_EQ(refused.error().code, DeviceErrorCode::NotSupported);
    EXPECT_THAT(refused.error().message, HasSubstr("/dev/video7: no Lepton answered"));
}

TEST(LeptonControlLink, TheLeptonSchemeOpensTheVideoNodeAndChecksItsUri) {
    // The kernel's extension units cannot be reached here: an absent node is the device error.
    auto absent = open_ffc_control("lepton:///dev/tirpol-no-such-video");
    ASSERT_FALSE(absent);
    EXPECT_THAT(absent.error().message, HasSubstr("/dev/tirpol-no-such-video"));
    EXPECT_THROW((void)open_ffc_control("lepton://video0"), Error);
    EXPECT_THROW((void)open_ffc_control("lepton:///dev/video0?ffc_timeout_ms=5"), Error);
    EXPECT_THROW((void)open_ffc_control("lepton:///dev/video0?timeout=1"), Error);
    try {
        (void)open_ffc_control("flir:///dev/video0");
        FAIL() << "accepted";
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), HasSubstr("lepton:///dev/video0"));
    }
}

}  // namespace
}  // namespace tirpol::acquisition
