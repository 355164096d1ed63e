// Stage::stop() from another thread during a homing or a move, against the stage simulator on a
// pseudo-terminal (APT MGMSG_MOT_MOVE_STOP, Elliptec `st`) and the in-process sim:// stage: the
// waiting call returns Stopped, the stage stays where it stopped (strictly between the start and
// the target, and still there a while later). And the APT simulator resynchronises after bytes of
// the wrong protocol or garbage, as a controller does.

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <future>
#include <thread>

#include "stage_simulator_thread.h"
#include "tirpol/acquisition/capture.h"
#include "tirpol/acquisition/internal/apt_protocol.h"
#include "tirpol/acquisition/internal/elliptec_protocol.h"
#include "tirpol/acquisition/sim/stage_simulator.h"
#include "tirpol/acquisition/stage.h"

namespace tirpol::acquisition {
namespace {

using namespace std::chrono_literals;

enum class Kind { Apt, Elliptec, Sim };

std::string kind_name(const ::testing::TestParamInfo<Kind>& p) {
    return p.param == Kind::Apt ? "Apt" : p.param == Kind::Elliptec ? "Elliptec" : "Sim";
}

/// A stage of `kind` turning at `deg_per_s` from 37.5° (the simulators' power-up angle).
struct SlowStage {
    SlowStage(Kind kind, double deg_per_s) {
        if (kind == Kind::Sim) {
            stage = open_stage(fmt::format("sim://?deg_per_s={}&start_deg=37.5", deg_per_s))
                        .value_or_throw();
            return;
        }
        StageSimulatorOptions o;
        o.protocol = kind == Kind::Apt ? SimProtocol::Apt : SimProtocol::Elliptec;
        o.deg_per_s = deg_per_s;
        sim = std::make_unique<test::StageSimulatorThread>(o);
        stage = open_stage((kind == Kind::Apt ? "thorlabs-apt://" : "elliptec://") + sim->path())
                    .value_or_throw();
    }
    std::unique_ptr<test::StageSimulatorThread> sim;
    std::unique_ptr<Stage> stage;
};

/// The angle read twice, 300 ms apart: a stopped stage reads the same both times.
std::pair<double, double> settled_position(Stage& stage) {
    const double first = stage.position_deg().value_or_throw();
    std::this_thread::sleep_for(300ms);
    return {first, stage.position_deg().value_or_throw()};
}

class StageStop : public ::testing::TestWithParam<Kind> {};

TEST_P(StageStop, StopsAHomingWhereItIsAndLeavesTheStageNotHomed) {
    SlowStage s(GetParam(), 10.0);  // homing from 37.5° to 0° takes 3.75 s
    auto homing = std::async(std::launch::async, [&] { return s.stage->home(60s); });
    std::this_thread::sleep_for(500ms);
    ASSERT_TRUE(s.stage->stop());
    const Status result = homing.get();
    ASSERT_FALSE(result);
    EXPECT_EQ(result.error().code, DeviceErrorCode::Stopped) << result.error().message;
    EXPECT_FALSE(s.stage->is_homed());
    const auto [first, later] = settled_position(*s.stage);
    EXPECT_GT(first, 0.5) << "the homing ran to the end";
    EXPECT_LT(first, 37.5) << "the homing never started";
    EXPECT_NEAR(later, first, 1e-9) << "the stage kept moving after the stop";
    // A stopped stage takes the next command: homing again completes.
    ASSERT_TRUE(s.stage->home(60s));
    EXPECT_TRUE(s.stage->is_homed());
}

TEST_P(StageStop, StopsAMoveWhereItIsAndTheNextMoveWorks) {
    SlowStage s(GetParam(), 20.0);
    s.stage->stop();  // harmless when nothing moves, and does not stop the next move
    ASSERT_TRUE(s.stage->home(60s));
    auto moving =
        std::async(std::launch::async, [&] { return s.stage->move_absolute(90.0, 60s); });  // 4.5 s
    std::this_thread::sleep_for(500ms);
    ASSERT_TRUE(s.stage->stop());
    const Status result = moving.get();
    ASSERT_FALSE(result);
    EXPECT_EQ(result.error().code, DeviceErrorCode::Stopped) << result.error().message;
    const auto [first, later] = settled_position(*s.stage);
    EXPECT_GT(first, 0.5);
    EXPECT_LT(first, 89.5);
    EXPECT_NEAR(later, first, 1e-9);
    ASSERT_TRUE(s.stage->move_absolute(first + 1.0, 60s));
    EXPECT_NEAR(s.stage->position_deg().value_or_throw(), first + 1.0, 0.01);
}

TEST_P(StageStop, StopOnInterruptStopsTheStageWhenTheFlagIsSet) {
    SlowStage s(GetParam(), 20.0);
    ASSERT_TRUE(s.stage->home(60s));
    std::atomic<bool> interrupt{false};
    std::atomic<bool> overdue{false};
    StopOnInterrupt watcher(interrupt, 60s, [&] { overdue = true; });
    watcher.watch(s.stage.get());
    auto moving = std::async(std::launch::async,
                             [&] { return s.stage->move_absolute(135.0, 60s); });  // 6.75 s
    std::this_thread::sleep_for(300ms);
    interrupt = true;  // what the SIGINT handler does
    const Status result = moving.get();
    ASSERT_FALSE(result);
    EXPECT_EQ(result.error().code, DeviceErrorCode::Stopped) << result.error().message;
    EXPECT_GE(watcher.stops_sent(), 1);
    EXPECT_LT(s.stage->position_deg().value_or_throw(), 134.5);
    EXPECT_FALSE(overdue);
}

INSTANTIATE_TEST_SUITE_P(Stages, StageStop, ::testing::Values(Kind::Apt, Kind::Elliptec, Kind::Sim),
                         kind_name);

TEST(StopOnInterrupt, CallsOnOverdueWhenTheProgramDoesNotFinishInTime) {
    std::atomic<bool> interrupt{false};
    std::atomic<int> overdue{0};
    {
        StopOnInterrupt watcher(interrupt, 100ms, [&] { ++overdue; });
        std::this_thread::sleep_for(200ms);
        EXPECT_EQ(overdue, 0) << "called without an interruption";
        interrupt = true;
        for (int i = 0; i < 500 && overdue == 0; ++i) std::this_thread::sleep_for(10ms);
    }
    EXPECT_EQ(overdue, 1);
    // A program that finishes (the watcher is destroyed) within the grace period is left alone.
    overdue = 0;
    {
        StopOnInterrupt watcher(interrupt, 60s, [&] { ++overdue; });
    }
    EXPECT_EQ(overdue, 0);
}

// ---- APT simulator resynchronisation ---------------------------------------------------------

std::vector<std::uint8_t> bytes_of(const std::string& s) { return {s.begin(), s.end()}; }

/// The messages in `bytes` as a driver decodes them.
std::vector<apt::Message> decode_all(std::vector<std::uint8_t> bytes) {
    std::vector<apt::Message> out;
    for (;;) {
        const auto d = apt::decode(bytes);
        if (d.status != apt::DecodeStatus::Complete) return out;
        out.push_back(d.message);
        bytes.erase(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(d.consumed));
    }
}

TEST(AptSimulatorResync, AnswersTheFirstValidRequestAfterAnElliptecProbeOrGarbage) {
    const std::vector<std::vector<std::uint8_t>> junk = {
        bytes_of("0in"),
        bytes_of("0in\r\n"),
        bytes_of("0in1in2in3in"),                    // Elliptec probes of three addresses
        {0xFF, 0x50, 0x01},                          // noise ending like a header tail
        {0x05, 0x00, 0x00, 0x00, 0x50},              // a request cut short
        {0x53, 0x04, 0x06, 0x00, 0xD0, 0x01, 0x01},  // a long header without its data
    };
    for (const auto& j : junk) {
        StageSimulator sim(StageSimulatorOptions{});
        const auto t = StageSimulator::Clock::now();
        auto out = sim.receive(j, t);
        const auto request = apt::hw_req_info();
        auto reply = sim.receive(request, t);
        out.insert(out.end(), reply.begin(), reply.end());
        // A cut-short long header may swallow the request as its data; the next request is
        // answered.
        if (decode_all(out).empty()) {
            reply = sim.receive(request, t);
            out.insert(out.end(), reply.begin(), reply.end());
        }
        const auto messages = decode_all(out);
        ASSERT_EQ(messages.size(), 1u) << "after " << j.size() << " junk bytes";
        EXPECT_EQ(messages[0].id, apt::kHwGetInfo);
        EXPECT_EQ(apt::parse_hw_info(messages[0])->model, "K10CR1");
        // And it keeps answering: the stream is aligned again.
        const auto status = decode_all(sim.receive(apt::mot_req_ustatus_update(), t));
        ASSERT_EQ(status.size(), 1u);
        EXPECT_EQ(status[0].id, apt::kMotGetUStatusUpdate);
    }
}

TEST(AptSimulatorResync, DecodeHostRequestRefusesHeadersNotFromTheHostToTheDevice) {
    const auto good = apt::hw_req_info();
    EXPECT_EQ(apt::decode_host_request(good).status, apt::DecodeStatus::Complete);
    const auto reply =
        apt::encode_short(apt::kHwReqInfo, 0, 0, apt::kHostAddress, apt::kUsbDeviceAddress);
    const auto d = apt::decode_host_request(reply);
    EXPECT_EQ(d.status, apt::DecodeStatus::Invalid);
    EXPECT_EQ(d.consumed, 1u);
    EXPECT_EQ(apt::decode_host_request(std::vector<std::uint8_t>{0x05, 0x00}).status,
              apt::DecodeStatus::NeedMore);
}

TEST(AptSimulatorResync, AnElliptecProbeOnTheAptPortDoesNotWedgeTheSimulator) {
    // What a user does who tries the wrong driver first: elliptec:// on a K10CR1's port.
    StageSimulatorOptions o;
    o.protocol = SimProtocol::Apt;
    o.deg_per_s = 3600.0;
    test::StageSimulatorThread sim(o);
    auto wrong = open_stage("elliptec://" + sim.path() + "?timeout_ms=300");
    ASSERT_FALSE(wrong);
    auto stage = open_stage("thorlabs-apt://" + sim.path() + "?timeout_ms=1000");
    ASSERT_TRUE(stage) << stage.error().message;
    EXPECT_EQ(stage.value()->info().model, "K10CR1");
    ASSERT_TRUE(stage.value()->home(5s));
    ASSERT_TRUE(stage.value()->move_absolute(45.0, 5s));
    EXPECT_NEAR(stage.value()->position_deg().value_or_throw(), 45.0, 1e-4);
}

TEST(ElliptecSimulatorResync, AnswersAfterAptBytes) {
    StageSimulatorOptions o;
    o.protocol = SimProtocol::Elliptec;
    StageSimulator sim(o);
    const auto t = StageSimulator::Clock::now();
    std::vector<std::uint8_t> in = apt::hw_req_info();
    const auto probe = bytes_of(elliptec::info_request('0'));
    in.insert(in.end(), probe.begin(), probe.end());
    const auto out = sim.receive(in, t);
    std::string text(out.begin(), out.end());
    const auto line = elliptec::take_line(text);
    ASSERT_TRUE(line);
    const auto reply = elliptec::parse_reply(*line);
    ASSERT_TRUE(reply);
    EXPECT_EQ(reply->code, "IN");
    EXPECT_TRUE(text.empty()) << "extra replies to the APT bytes: " << text;
}

}  // namespace
}  // namespace tirpol::acquisition
