// The Boson control-link driver against the simulated core on a pseudo-terminal: the real FSLP
// bytes through the real serial-port code. Reference bytes: frames captured from a Boson on
// /dev/ttyACM0 and published in github.com/thurberdog/ghostCommand (README.md): BOSON_GETCAMERASN
// with sequence 1 and its reply (serial 0x00016D94), BOSON_LOOKUPFPATEMPDEGCX10's reply 0x017C
// (38.0 °C).

#include "tirpol/acquisition/internal/boson_control.h"

#include <gtest/gtest.h>

#include <thread>

#include "pty_device_thread.h"
#include "tirpol/acquisition/internal/boson_simulator.h"
#include "tirpol/acquisition/internal/serial_port.h"

namespace tirpol::acquisition {
namespace {

using namespace std::chrono_literals;
using namespace boson;
using SimThread = test::PtyDeviceThread<BosonSimulator>;
using Clock = std::chrono::steady_clock;

std::shared_ptr<BosonCoreModel> make_core(BosonCoreConfig config = {}) {
    return std::make_shared<BosonCoreModel>(std::move(config));
}

std::unique_ptr<BosonControl> connect(const SimThread& sim, BosonControlOptions options = {}) {
    return open_boson_control(sim.path(), "boson-sim", options).value_or_throw();
}

TEST(BosonControl, EncodesAndDecodesFramesCapturedFromARealBoson) {
    const std::vector<std::uint8_t> sent = {0x8E, 0x00, 0x00, 0x00, 0x00, 0x01, 0x00, 0x05, 0x00,
                                            0x02, 0xFF, 0xFF, 0xFF, 0xFF, 0x01, 0x0B, 0xAE};
    EXPECT_EQ(encode_command({1, kBosonGetCameraSn, {}}), sent);
    const std::vector<std::uint8_t> serial_reply = {0x8E, 0x00, 0x00, 0x00, 0x00, 0x01, 0x00,
                                                    0x05, 0x00, 0x02, 0x00, 0x00, 0x00, 0x00,
                                                    0x00, 0x01, 0x6D, 0x94, 0x30, 0x10, 0xAE};
    const std::vector<std::uint8_t> fpa_reply = {0x8E, 0x00, 0x00, 0x00, 0x00, 0x01, 0x00,
                                                 0x05, 0x00, 0x30, 0x00, 0x00, 0x00, 0x00,
                                                 0x01, 0x7C, 0xBD, 0xCE, 0xAE};
    FrameDecoder decoder;
    auto frames = decoder.feed(serial_reply);
    ASSERT_EQ(frames.size(), 1u);
    ASSERT_EQ(frames[0].status, FrameStatus::Ok) << describe(frames[0]);
    auto reply = parse_reply(frames[0].payload);
    ASSERT_TRUE(reply);
    EXPECT_EQ(read_u32(reply->data, 0), 93588u);
    frames = decoder.feed(fpa_reply);
    ASSERT_EQ(frames.size(), 1u);
    ASSERT_EQ(frames[0].status, FrameStatus::Ok) << describe(frames[0]);
    EXPECT_EQ(static_cast<std::int16_t>(read_u16(parse_reply(frames[0].payload)->data, 0)), 380);
}

TEST(BosonControl, ReadsIdentityAndFpaTemperature) {
    BosonCoreConfig config;
    config.fpa_start_k = 311.15;  // 38.0 °C
    SimThread sim(make_core(config));
    auto boson = connect(sim);
    EXPECT_EQ(boson->camera_serial().value(), 93588u);
    EXPECT_EQ(boson->part_number().value(), "20640A050-6IAAX");
    EXPECT_NEAR(boson->fpa_temperature_k().value(), 311.15, 1e-9);  // 380 × 0.1 °C + 273.15
}

TEST(BosonControl, SetsModesAndReportsTheCoresRefusalByName) {
    SimThread sim(make_core());
    auto boson = connect(sim);
    EXPECT_EQ(boson->ffc_mode().value(), FfcMode::Auto);
    ASSERT_TRUE(boson->set_ffc_mode(FfcMode::Manual));
    EXPECT_EQ(boson->ffc_mode().value(), FfcMode::Manual);
    EXPECT_EQ(sim.device().core()->ffc_mode(), FfcMode::Manual);
    ASSERT_TRUE(boson->set_gain_mode(GainMode::Low));
    EXPECT_EQ(boson->gain_mode().value(), GainMode::Low);
    ASSERT_TRUE(boson->set_ffc_temperature_threshold_k(0.7));
    EXPECT_NEAR(boson->ffc_temperature_threshold_k().value(), 0.7, 1e-9);

    std::vector<std::uint8_t> seven;
    append_u32(seven, 7);
    auto refused = boson->transact(kBosonSetFfcMode, seven, 0);
    ASSERT_FALSE(refused);
    EXPECT_EQ(refused.error().code, DeviceErrorCode::DeviceFault);
    EXPECT_NE(refused.error().message.find("R_CAM_API_INVALID_INPUT"), std::string::npos)
        << refused.error().message;
    auto unknown = boson->transact(0x00051234, {}, 0);
    ASSERT_FALSE(unknown);
    EXPECT_NE(unknown.error().message.find("R_CAM_DSPCH_BAD_CMD_ID"), std::string::npos)
        << unknown.error().message;
    // The link still works after refusals.
    EXPECT_EQ(boson->gain_mode().value(), GainMode::Low);
}

TEST(BosonControl, ManualFfcClosesTheShutterForItsDurationAndMovesTheLastFfcFrameCount) {
    BosonCoreConfig config;
    config.ffc_duration_s = 0.5;
    config.frame_rate_hz = 60.0;
    SimThread sim(make_core(config));
    auto boson = connect(sim);
    ASSERT_TRUE(boson->set_ffc_mode(FfcMode::Manual));
    EXPECT_EQ(boson->ffc_status().value(), FfcStatus::NoFfcPerformed);
    std::this_thread::sleep_for(100ms);
    const auto t0 = Clock::now();
    ASSERT_TRUE(boson->run_ffc());
    EXPECT_TRUE(boson->ffc_in_progress().value());
    EXPECT_EQ(boson->ffc_status().value(), FfcStatus::InProgress);
    while (boson->ffc_in_progress().value()) std::this_thread::sleep_for(10ms);
    const double took_s = std::chrono::duration<double>(Clock::now() - t0).count();
    EXPECT_GE(took_s, 0.5 - 0.02);  // the simulated shutter stays closed for ffc_duration_s
    const auto state = boson->ffc_state().value();
    EXPECT_EQ(state.status, FfcStatus::Complete);
    EXPECT_GT(state.last_ffc_frame_count, 0u);
    EXPECT_GE(state.frame_count,
              state.last_ffc_frame_count + 25);  // ≥ 0.5 s at 60 Hz after the FFC began
    ASSERT_TRUE(boson->run_ffc_and_wait());
    EXPECT_GT(boson->last_ffc_frame_count().value(), state.last_ffc_frame_count);
    EXPECT_EQ(sim.device().core()->ffcs_started(Clock::now()), 2);
}

TEST(BosonControl, AutoFfcRunsWhenTheFpaMovesByTheThresholdAndNotInManualMode) {
    BosonCoreConfig config;
    config.ffc_threshold_k = 0.5;
    SimThread sim(make_core(config));
    auto boson = connect(sim);
    auto core = sim.device().core();
    ASSERT_TRUE(boson->set_ffc_mode(FfcMode::Manual));
    core->add_fpa_step_k(0.6);
    std::this_thread::sleep_for(50ms);
    EXPECT_EQ(boson->last_ffc_frame_count().value(), 0u);
    EXPECT_FALSE(boson->ffc_in_progress().value());
    ASSERT_TRUE(
        boson->set_ffc_mode(FfcMode::Auto));  // the FPA is now 0.6 K from the power-up reference
    std::this_thread::sleep_for(50ms);
    EXPECT_TRUE(boson->ffc_in_progress().value());
    EXPECT_EQ(core->auto_ffcs_started(Clock::now()), 1);
    EXPECT_GT(boson->last_ffc_frame_count().value(), 0u);
    core->add_fpa_step_k(0.3);  // below the threshold from the new reference: no second FFC
    std::this_thread::sleep_for(700ms);
    EXPECT_EQ(boson->ffc_status().value(), FfcStatus::Complete);
    EXPECT_EQ(core->auto_ffcs_started(Clock::now()), 1);
}

struct FaultCase {
    BosonSimFault fault;
    DeviceErrorCode code;
    const char* message_part;
};

class BosonControlFault : public ::testing::TestWithParam<FaultCase> {};

TEST_P(BosonControlFault, IsAClearErrorAndTheLinkRecoversUnlessSilent) {
    BosonSimulatorOptions options;
    options.fault = GetParam().fault;
    options.fault_on_command = 3;  // open (1: serial) and one more command pass
    SimThread sim(make_core(), options);
    BosonControlOptions driver;
    driver.reply_timeout = 200ms;
    auto boson = connect(sim, driver);
    ASSERT_TRUE(boson->gain_mode());
    const auto t0 = Clock::now();
    auto failed = boson->fpa_temperature_k();
    ASSERT_FALSE(failed);
    EXPECT_EQ(failed.error().code, GetParam().code) << failed.error().message;
    EXPECT_NE(failed.error().message.find(GetParam().message_part), std::string::npos)
        << failed.error().message;
    EXPECT_NE(failed.error().message.find("BOSON_LOOKUPFPATEMPDEGCX10"), std::string::npos)
        << failed.error().message;
    if (GetParam().code == DeviceErrorCode::Timeout) {
        EXPECT_GE(Clock::now() - t0, 190ms);
    }
    auto next = boson->camera_serial();
    if (GetParam().fault == BosonSimFault::Silent) {
        ASSERT_FALSE(next);
        EXPECT_EQ(next.error().code, DeviceErrorCode::Timeout);
    } else {
        EXPECT_EQ(next.value(), 93588u);
    }
}

INSTANTIATE_TEST_SUITE_P(
    Faults, BosonControlFault,
    ::testing::Values(
        FaultCase{BosonSimFault::DropReply, DeviceErrorCode::Timeout, "stopped answering"},
        FaultCase{BosonSimFault::Silent, DeviceErrorCode::Timeout, "stopped answering"},
        FaultCase{BosonSimFault::CorruptCrc, DeviceErrorCode::BadReply, "bad CRC"},
        FaultCase{BosonSimFault::WrongSequence, DeviceErrorCode::BadReply, "carries sequence"}));

TEST(BosonControl, AbsentPortIsAnErrorNamingIt) {
    auto r = open_boson_control("/dev/nonexistent-boson", "boson:///dev/nonexistent-boson");
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().message.find("/dev/nonexistent-boson"), std::string::npos)
        << r.error().message;
}

}  // namespace
}  // namespace tirpol::acquisition
