// Requires TIRPOL_WITH_ARAVIS (built only with that back end: cmake/TirpolBackends.cmake).
// The aravis:// camera against Aravis's own fake GigE Vision camera (arv-fake-gv-camera-0.8,
// started here on 127.0.0.1). Pixel values are checked against the fake's published test pattern,
// Aravis 0.8.26 src/arvfakecamera.c arv_fake_camera_diagonal_ramp: Mono16 pixel (x, y) of frame id
// f is (256 x + 256 f + 256 y) mod 65535, times 1 + gain + log10(exposure_us / 10000) (= 1 by
// default). Frame ids start at 65401 and wrap 65535 → 1 (arv_fake_camera_init: "Trigger circular
// counter bugs sooner").

#include "tirpol/acquisition/internal/aravis_camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <thread>

#include "fake_gv_camera_process.h"
#include "test_support.h"
#include "tirpol/acquisition/frame_gate.h"

namespace tirpol::acquisition {
namespace {

using namespace std::chrono_literals;

std::uint64_t raw_gvsp_id(std::uint64_t unwrapped) { return (unwrapped - 1) % 65535 + 1; }

float diagonal_ramp_mono16(int x, int y, std::uint64_t raw_id) {
    return static_cast<float>(
        (256 * static_cast<std::uint64_t>(x) + 256 * raw_id + 256 * static_cast<std::uint64_t>(y)) %
        65535);
}

/// Every pixel of `frame` equals the fake camera's Mono16 test pattern for the frame's own id.
bool matches_diagonal_ramp(const Frame& frame) {
    const std::uint64_t raw = raw_gvsp_id(frame.frame_id);
    for (int y = 0; y < frame.height; ++y)
        for (int x = 0; x < frame.width; ++x)
            if (frame.counts[static_cast<std::size_t>(y * frame.width + x)] !=
                diagonal_ramp_mono16(x, y, raw))
                return false;
    return true;
}

std::filesystem::path thermal_xml() {
    return test::source_dir() / "tests/data/genicam/thermal-fake-camera.xml";
}

class AravisFakeCamera : public ::testing::Test {
protected:
    /// Starts the fake camera with `args`; fails the test when aravis-tools is not installed (never
    /// skips).
    void start_fake(const std::vector<std::string>& args = {}) {
        const auto binary = test::find_fake_gv_camera_binary();
        if (!binary)
            FAIL() << test::kFakeGvCameraBinary
                   << " not found on PATH: install the Debian package aravis-tools (./run does)";
        m_process = std::make_unique<test::FakeGvCameraProcess>(*binary, args);
        ASSERT_TRUE(m_process->ready())
            << "the fake GigE Vision camera did not answer on 127.0.0.1";
    }

    std::unique_ptr<Camera> open(const AravisCameraOptions& options) {
        auto camera = open_aravis_camera(test::kFakeGvCameraId, options);
        EXPECT_TRUE(camera.ok()) << (camera.ok() ? "" : camera.error().message);
        return camera.ok() ? std::move(camera.value()) : nullptr;
    }

    test::LoopbackGigELock m_lock;
    std::unique_ptr<test::FakeGvCameraProcess> m_process;
};

AravisCameraOptions small_mono16(double fps = 200.0) {
    AravisCameraOptions o;
    o.pixel_format = "Mono16";
    o.width = 64;
    o.height = 48;
    o.frame_rate_hz = fps;
    return o;
}

TEST_F(AravisFakeCamera, DiscoveryFindsTheFakeCameraOnLoopback) {
    start_fake();
    if (HasFatalFailure() || IsSkipped()) return;
    const auto devices = discover_aravis_cameras();
    const auto it = std::find_if(devices.begin(), devices.end(), [](const AravisDeviceInfo& d) {
        return d.id == test::kFakeGvCameraId;
    });
    ASSERT_NE(it, devices.end());
    EXPECT_EQ(it->vendor, "Aravis");
    EXPECT_EQ(it->model, "Fake");
    EXPECT_EQ(it->address, "127.0.0.1");
    EXPECT_EQ(it->protocol, "GigEVision");
}

TEST_F(AravisFakeCamera, ConfiguresAndDeliversTheTestPatternWithConsecutiveIds) {
    start_fake();
    if (HasFatalFailure() || IsSkipped()) return;
    auto camera = open(small_mono16());
    ASSERT_TRUE(camera);
    const CameraInfo info = camera->info();
    EXPECT_EQ(info.uri, std::string("aravis://") + test::kFakeGvCameraId);
    EXPECT_EQ(info.vendor, "Aravis");
    EXPECT_EQ(info.pixel_format, "Mono16");
    EXPECT_EQ(info.bits_per_pixel, 16);
    EXPECT_EQ(info.width, 64);
    EXPECT_EQ(info.height, 48);
    ASSERT_TRUE(info.frame_rate_hz);
    EXPECT_DOUBLE_EQ(*info.frame_rate_hz, 200.0);  // period register 1e6 / 200 = 5000 µs exactly
    EXPECT_TRUE(info.planck_constants.empty());    // the stock fake XML has none

    ASSERT_TRUE(camera->start().ok());
    std::vector<Frame> frames;
    for (int i = 0; i < 20; ++i) {
        auto frame = camera->grab(2s);
        ASSERT_TRUE(frame.ok()) << frame.error().message;
        frames.push_back(std::move(frame.value()));
    }
    ASSERT_TRUE(camera->stop().ok());
    for (std::size_t i = 0; i < frames.size(); ++i) {
        EXPECT_EQ(frames[i].width, 64);
        EXPECT_EQ(frames[i].height, 48);
        EXPECT_TRUE(matches_diagonal_ramp(frames[i])) << "frame " << frames[i].frame_id;
        EXPECT_GT(frames[i].host_timestamp_ns, 0);
        if (i > 0) {
            EXPECT_GT(frames[i].frame_id, frames[i - 1].frame_id);
            EXPECT_GT(frames[i].device_timestamp_ns, frames[i - 1].device_timestamp_ns);
        }
    }
    const StreamStatistics stats = camera->statistics();
    EXPECT_EQ(stats.delivered, 20u);
    // Accounting: every id between the first and last frame is delivered, damaged or lost (on an
    // idle loopback all are delivered; damaged frames before the first good one only add to
    // `incomplete`).
    const std::uint64_t span = frames.back().frame_id - frames.front().frame_id + 1;
    EXPECT_LE(stats.delivered + stats.dropped, span);
    EXPECT_GE(stats.delivered + stats.incomplete + stats.dropped, span);
}

TEST_F(AravisFakeCamera, FrameIdWrapAt65535IsUnwrappedToMonotonicIds) {
    start_fake();
    if (HasFatalFailure() || IsSkipped()) return;
    auto camera = open(small_mono16(500.0));
    ASSERT_TRUE(camera);
    ASSERT_TRUE(camera->start().ok());
    // Ids start at 65401: 200 frames cross 65535 → 1.
    std::uint64_t first = 0, previous = 0;
    bool crossed = false;
    for (int i = 0; i < 200; ++i) {
        auto frame = camera->grab(2s);
        ASSERT_TRUE(frame.ok()) << frame.error().message;
        const Frame& f = frame.value();
        if (i == 0)
            first = f.frame_id;
        else
            ASSERT_GT(f.frame_id, previous);
        if (f.frame_id > 65535) crossed = true;
        ASSERT_TRUE(matches_diagonal_ramp(f))
            << "frame " << f.frame_id;  // the pattern uses the raw 16-bit id
        previous = f.frame_id;
    }
    EXPECT_LT(first, 65535u);
    EXPECT_TRUE(crossed);
    const StreamStatistics stats = camera->statistics();
    EXPECT_LE(stats.delivered + stats.dropped, previous - first + 1);
    EXPECT_GE(stats.delivered + stats.incomplete + stats.dropped, previous - first + 1);
}

TEST_F(AravisFakeCamera, AveragingFramesGivesTheMeanOfThePattern) {
    start_fake();
    if (HasFatalFailure() || IsSkipped()) return;
    auto camera = open(small_mono16());
    ASSERT_TRUE(camera);
    ASSERT_TRUE(camera->start().ok());
    FrameAverager averager;
    std::vector<std::uint64_t> ids;
    for (int i = 0; i < 8; ++i) {
        auto frame = camera->grab(2s);
        ASSERT_TRUE(frame.ok()) << frame.error().message;
        averager.add(frame.value());
        ids.push_back(raw_gvsp_id(frame.value().frame_id));
    }
    const auto mean = averager.mean();
    const auto std = averager.stddev();
    for (int y = 0; y < 48; y += 7) {
        for (int x = 0; x < 64; x += 5) {
            double sum = 0.0, sum2 = 0.0;
            for (auto id : ids) sum += diagonal_ramp_mono16(x, y, id);
            const double m = sum / static_cast<double>(ids.size());
            for (auto id : ids) sum2 += std::pow(diagonal_ramp_mono16(x, y, id) - m, 2);
            const std::size_t i = static_cast<std::size_t>(y * 64 + x);
            EXPECT_NEAR(mean[i], m, 1e-3 * std::max(1.0, m));
            EXPECT_NEAR(std[i], std::sqrt(sum2 / static_cast<double>(ids.size() - 1)), 1e-2);
        }
    }
}

TEST_F(AravisFakeCamera, PacketLossIsCountedAndAcquisitionStillCompletes) {
    start_fake({"-r", "40"});  // 4 % of GVSP packets dropped by the fake camera
    if (HasFatalFailure() || IsSkipped()) return;
    auto camera = open(small_mono16());
    ASSERT_TRUE(camera);
    ASSERT_TRUE(camera->start().ok());
    std::vector<Frame> frames;
    while (frames.size() < 60) {
        auto frame = camera->grab(5s);
        ASSERT_TRUE(frame.ok()) << frame.error().message;
        ASSERT_TRUE(matches_diagonal_ramp(frame.value())) << "a damaged frame was delivered";
        if (!frames.empty()) {
            ASSERT_GT(frame.value().frame_id, frames.back().frame_id);
        }
        frames.push_back(std::move(frame.value()));
    }
    ASSERT_TRUE(camera->stop().ok());
    const StreamStatistics stats = camera->statistics();
    EXPECT_EQ(stats.delivered, 60u);
    // 64×48 Mono16 is a leader, 5 data packets and a trailer: P(frame intact) = 0.96^7 ≈ 0.75, so
    // 60 good frames without a single loss has probability ≈ 0.75^60 ≈ 3e-8.
    EXPECT_GT(stats.incomplete + stats.dropped, 0u);
    // Damaged frames before the first good one are counted but lie outside [first, last].
    EXPECT_GE(stats.delivered + stats.incomplete + stats.dropped,
              frames.back().frame_id - frames.front().frame_id + 1);
    EXPECT_LE(stats.delivered + stats.dropped,
              frames.back().frame_id - frames.front().frame_id + 1);
}

TEST_F(AravisFakeCamera, ThermalGenicamExposesMono14TemperatureAndPlanckConstants) {
    start_fake({"-g", thermal_xml().string()});
    if (HasFatalFailure() || IsSkipped()) return;
    AravisCameraOptions options = small_mono16();
    options.pixel_format = "Mono14";
    auto camera = open(options);
    ASSERT_TRUE(camera);
    const CameraInfo info = camera->info();
    EXPECT_EQ(info.pixel_format, "Mono14");
    EXPECT_EQ(info.bits_per_pixel, 14);
    // Constants of tests/data/genicam/thermal-fake-camera.xml.
    ASSERT_EQ(info.planck_constants.size(), 5u);
    EXPECT_DOUBLE_EQ(info.planck_constants.at("R1"), 21106.77);
    EXPECT_DOUBLE_EQ(info.planck_constants.at("R2"), 0.012545258);
    EXPECT_DOUBLE_EQ(info.planck_constants.at("B"), 1501.0);
    EXPECT_DOUBLE_EQ(info.planck_constants.at("F"), 1.0);
    EXPECT_DOUBLE_EQ(info.planck_constants.at("O"), -7340.0);
    // DeviceTemperature is in °C (SFNC): 35.25 °C = 308.40 K.
    ASSERT_TRUE(camera->device_temperature_k());
    EXPECT_NEAR(*camera->device_temperature_k(), 308.40, 1e-9);
    ASSERT_TRUE(camera->start().ok());
    auto frame = camera->grab(2s);
    ASSERT_TRUE(frame.ok()) << frame.error().message;
    // Aravis's test pattern has no Mono14 case, so only the geometry and metadata are checked here.
    EXPECT_EQ(frame.value().width, 64);
    EXPECT_EQ(frame.value().counts.size(), 64u * 48u);
    ASSERT_TRUE(frame.value().fpa_temperature_k);
    EXPECT_NEAR(*frame.value().fpa_temperature_k, 308.40, 1e-9);
}

/// The thermal XML with its Float AcquisitionFrameRate replaced by `replacement`.
std::filesystem::path xml_with_frame_rate_node(const test::TempDir& dir,
                                               const std::string& replacement) {
    std::ifstream in(thermal_xml());
    std::stringstream text;
    text << in.rdbuf();
    std::string xml = text.str();
    const std::string open_tag = R"(<Float Name="AcquisitionFrameRate">)", close_tag = "</Float>";
    const auto begin = xml.find(open_tag);
    EXPECT_NE(begin, std::string::npos);
    const auto end = xml.find(close_tag, begin);
    if (begin != std::string::npos && end != std::string::npos)
        xml.replace(begin, end + close_tag.size() - begin, replacement);
    const auto path = dir / "variant.xml";
    test::write_text(path, xml);
    return path;
}

TEST_F(AravisFakeCamera, FrameRateFallsBackToAcquisitionFrameRateAbs) {
    test::TempDir dir;
    const auto xml = xml_with_frame_rate_node(
        dir,
        R"(<Float Name="AcquisitionFrameRateAbs"><pValue>AcquisitionFrameRateConverter</pValue></Float>)");
    start_fake({"-g", xml.string()});
    if (HasFatalFailure() || IsSkipped()) return;
    auto camera = open({});
    ASSERT_TRUE(camera);
    ASSERT_TRUE(camera->set_frame_rate(50.0).ok());
    ASSERT_TRUE(camera->info().frame_rate_hz);
    EXPECT_DOUBLE_EQ(*camera->info().frame_rate_hz, 50.0);
}

TEST_F(AravisFakeCamera, FrameRateEnumerationOnlyPicksTheMatchingEntry) {
    test::TempDir dir;
    // Like a thermal core with fixed rates: entries are frame periods in µs of the fake's period
    // register.
    const auto xml = xml_with_frame_rate_node(dir, R"(<Enumeration Name="IRFrameRate">
		<EnumEntry Name="Rate25Hz"><Value>40000</Value></EnumEntry>
		<EnumEntry Name="Rate7_5Hz"><Value>133333</Value></EnumEntry>
		<EnumEntry Name="Rate50Hz"><Value>20000</Value></EnumEntry>
		<pValue>AcquisitionFramePeriodRegister</pValue>
	</Enumeration>)");
    start_fake({"-g", xml.string()});
    if (HasFatalFailure() || IsSkipped()) return;
    auto camera = open({});
    ASSERT_TRUE(camera);
    ASSERT_TRUE(camera->set_frame_rate(7.5).ok());
    EXPECT_DOUBLE_EQ(camera->info().frame_rate_hz.value_or(0.0), 7.5);
    ASSERT_TRUE(camera->set_frame_rate(50.0).ok());
    EXPECT_DOUBLE_EQ(camera->info().frame_rate_hz.value_or(0.0), 50.0);
    const Status refused = camera->set_frame_rate(30.0);
    ASSERT_FALSE(refused.ok());
    EXPECT_EQ(refused.error().code, DeviceErrorCode::InvalidArgument);
    EXPECT_NE(refused.error().message.find("Rate25Hz"), std::string::npos)
        << refused.error().message;
    // The camera streams at the rate chosen through the enumeration.
    ASSERT_TRUE(camera->start().ok());
    EXPECT_TRUE(camera->grab(2s).ok());
}

TEST_F(AravisFakeCamera, FrameRateOutsideTheFeatureRangeIsRefused) {
    start_fake();
    if (HasFatalFailure() || IsSkipped()) return;
    auto camera = open({});
    ASSERT_TRUE(camera);
    // AcquisitionFramePeriod has Min 1000 µs in arv-fake-camera.xml: at most 1000 Hz.
    const Status s = camera->set_frame_rate(5000.0);
    ASSERT_FALSE(s.ok());
    EXPECT_EQ(s.error().code, DeviceErrorCode::InvalidArgument);
}

TEST_F(AravisFakeCamera, SoftwareTriggerDeliversAFrameTakenAfterTheTrigger) {
    start_fake();
    if (HasFatalFailure() || IsSkipped()) return;
    AravisCameraOptions options = small_mono16();
    options.software_trigger = true;
    auto camera = open(options);
    ASSERT_TRUE(camera);
    ASSERT_TRUE(camera->start().ok());
    for (int i = 0; i < 3; ++i) {
        // Free running, frames would queue up during this pause and the next grab would return an
        // old one.
        std::this_thread::sleep_for(100ms);
        timespec now{};
        clock_gettime(CLOCK_REALTIME, &now);
        const std::int64_t before_ns =
            static_cast<std::int64_t>(now.tv_sec) * 1'000'000'000 + now.tv_nsec;
        auto frame = camera->grab(2s);
        ASSERT_TRUE(frame.ok()) << frame.error().message;
        // The fake stamps frames with g_get_real_time() (µs) when it fills them.
        EXPECT_GE(frame.value().device_timestamp_ns, before_ns / 1000 * 1000);
        EXPECT_TRUE(matches_diagonal_ramp(frame.value()));
    }
}

TEST_F(AravisFakeCamera, UnsupportedPixelFormatsAreRefusedWithTheChoices) {
    start_fake();
    if (HasFatalFailure() || IsSkipped()) return;
    auto camera = open({});
    ASSERT_TRUE(camera);
    const Status packed = camera->set_pixel_format("RGB8");
    ASSERT_FALSE(packed.ok());
    EXPECT_EQ(packed.error().code, DeviceErrorCode::InvalidArgument);
    const Status absent = camera->set_pixel_format("Mono14");  // not in the stock fake XML
    ASSERT_FALSE(absent.ok());
    EXPECT_EQ(absent.error().code, DeviceErrorCode::NotSupported);
    EXPECT_NE(absent.error().message.find("Mono16"), std::string::npos) << absent.error().message;
}

TEST(AravisCamera, OpeningAnAbsentDeviceIsADeviceErrorWithGErrorDomainAndCode) {
    auto camera = open_aravis_camera("No-Such-Camera-0000");
    ASSERT_FALSE(camera.ok());
    EXPECT_NE(camera.error().message.find("aravis://No-Such-Camera-0000"), std::string::npos);
    EXPECT_NE(camera.error().message.find("GError domain"), std::string::npos)
        << camera.error().message;
}

TEST(AravisCamera, FrameRateIsParsedFromEnumerationEntryNames) {
    EXPECT_EQ(frame_rate_from_entry_name("Rate30Hz"), 30.0);
    EXPECT_EQ(frame_rate_from_entry_name("Rate7_5Hz"), 7.5);
    EXPECT_EQ(frame_rate_from_entry_name("Hz_60"), 60.0);
    EXPECT_EQ(frame_rate_from_entry_name("8p3Hz"), 8.3);
    EXPECT_EQ(frame_rate_from_entry_name("Fastest"), std::nullopt);
}

}  // namespace
}  // namespace tirpol::acquisition
