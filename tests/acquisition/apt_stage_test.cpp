// APT stage logic against scripted controller replies (a test double for the byte port), for the
// cases the simulator does not produce: replies split across reads, unsolicited status messages in
// between, garbage before a header, MOVE_STOPPED. Plus the simulator engine's move timing on a
// synthetic clock: a move of Δθ at speed v completes after Δθ/v (+ latency), not before.

#include "tirpol/acquisition/internal/apt_stage.h"

#include <gtest/gtest.h>

#include <deque>

#include "tirpol/acquisition/internal/apt_protocol.h"
#include "tirpol/acquisition/sim/stage_simulator.h"

namespace tirpol::acquisition {
namespace {

using namespace std::chrono_literals;
using Bytes = std::vector<std::uint8_t>;

/// Test double: every write pops the next scripted reply, delivered in the given chunks.
class ScriptedPort final : public BytePort {
public:
    struct Shared {
        std::deque<std::vector<Bytes>> replies;  ///< per write: chunks returned by successive reads
        std::vector<Bytes> written;
    };
    explicit ScriptedPort(Shared& s) : m_s(s) {}
    Status write(std::span<const std::uint8_t> bytes, std::chrono::milliseconds) override {
        m_s.written.emplace_back(bytes.begin(), bytes.end());
        if (!m_s.replies.empty()) {
            for (auto& chunk : m_s.replies.front()) m_pending.push_back(chunk);
            m_s.replies.pop_front();
        }
        return ok_status();
    }
    Result<Bytes> read_some(std::chrono::milliseconds) override {
        if (m_pending.empty())
            return DeviceError{DeviceErrorCode::Timeout, "scripted: nothing to read"};
        Bytes b = m_pending.front();
        m_pending.pop_front();
        return b;
    }
    Status discard_input() override { return ok_status(); }
    std::string name() const override { return "scripted"; }

private:
    Shared& m_s;
    std::deque<Bytes> m_pending;
};

Bytes concat(std::initializer_list<Bytes> parts) {
    Bytes out;
    for (const auto& p : parts) out.insert(out.end(), p.begin(), p.end());
    return out;
}

std::unique_ptr<Stage> open_scripted(ScriptedPort::Shared& s, std::uint32_t status_bits_at_open) {
    apt::HardwareInfo info;
    info.serial = 27000001;
    info.model = "K10CR1";
    const Bytes get_info = apt::hw_get_info(info);
    s.replies.push_back({});  // NO_FLASH_PROGRAMMING: no reply
    s.replies.push_back(
        {Bytes(get_info.begin(), get_info.begin() + 10),  // GET_INFO split in two reads
         Bytes(get_info.begin() + 10, get_info.end())});
    s.replies.push_back({});  // SET_CHANENABLESTATE: no reply
    s.replies.push_back(
        {apt::status_message(apt::kMotGetUStatusUpdate, {1, 0, 0, 0, status_bits_at_open})});
    return open_apt_stage(std::make_unique<ScriptedPort>(s), "scripted://k10cr1").value_or_throw();
}

TEST(AptStage, OpeningReadsIdentityAndTheHomedBitSurvivesAcrossSessions) {
    ScriptedPort::Shared s;
    auto stage = open_scripted(s, apt::kHomed | apt::kChannelEnabled);
    EXPECT_EQ(stage->info().serial, "27000001");
    EXPECT_TRUE(stage->is_homed());  // homed in an earlier session: no second homing needed
    ASSERT_EQ(s.written.size(), 4u);
    EXPECT_EQ(s.written[0], apt::hw_no_flash_programming());
    EXPECT_EQ(s.written[1], apt::hw_req_info());
    EXPECT_EQ(s.written[2], apt::mod_set_chan_enable_state(1, true));
    EXPECT_EQ(s.written[3], apt::mot_req_ustatus_update(1));
}

TEST(AptStage, MoveSkipsUnsolicitedMessagesAndGarbageUntilMoveCompleted) {
    ScriptedPort::Shared s;
    auto stage = open_scripted(s, apt::kHomed);
    const std::int32_t target = 6144000;  // 45° × 409600/3
    s.replies.push_back(
        {concat({apt::status_message(apt::kMotGetUStatusUpdate, {1, 100, 5, 0, apt::kMovingCw}),
                 Bytes{0xFF, 0x00}}),  // two bytes of line noise
         apt::status_message(apt::kMotMoveCompleted, {1, target, 0, 0, apt::kHomed})});
    const auto moved = stage->move_absolute(45.0, 1s);
    ASSERT_TRUE(moved) << moved.error().message;
    EXPECT_EQ(s.written.back(), apt::mot_move_absolute(target));
}

TEST(AptStage, MoveStoppedAndMotionErrorAreDeviceFaults) {
    ScriptedPort::Shared s;
    auto stage = open_scripted(s, apt::kHomed);
    s.replies.push_back({apt::status_message(apt::kMotMoveStopped, {1, 1000, 0, 0, apt::kHomed})});
    auto moved = stage->move_absolute(90.0, 1s);
    ASSERT_FALSE(moved);
    EXPECT_EQ(moved.error().code, DeviceErrorCode::DeviceFault);
    EXPECT_NE(moved.error().message.find("stopped at"), std::string::npos);
    s.replies.push_back({apt::status_message(apt::kMotMoveCompleted,
                                             {1, 1000, 0, 0, apt::kHomed | apt::kMotionError})});
    moved = stage->move_absolute(90.0, 1s);
    ASSERT_FALSE(moved);
    EXPECT_NE(moved.error().message.find("motion error"), std::string::npos);
}

TEST(AptStage, AMoveBeforeHomingIsRefusedWithoutTouchingTheDevice) {
    ScriptedPort::Shared s;
    auto stage = open_scripted(s, 0);
    const std::size_t writes = s.written.size();
    const auto moved = stage->move_absolute(45.0, 1s);
    ASSERT_FALSE(moved);
    EXPECT_EQ(moved.error().code, DeviceErrorCode::InvalidArgument);
    EXPECT_EQ(s.written.size(), writes);
}

TEST(StageSimulatorEngine, MoveCompletesAfterDistanceOverSpeed) {
    StageSimulatorOptions o;
    o.protocol = SimProtocol::Apt;
    o.deg_per_s = 10.0;  // a K10CR1
    o.start_deg = 0.0;
    o.latency = 5ms;
    StageSimulator sim(o);
    const auto t0 = StageSimulator::Clock::time_point{} + 1h;
    EXPECT_TRUE(sim.receive(apt::mot_move_home(), t0).empty());
    const auto homed = sim.poll(t0 + 5ms);
    EXPECT_EQ(apt::decode(homed).message.id, apt::kMotMoveHomed);
    // 0° → 45° at 10°/s: 4.5 s.
    const auto t1 = t0 + 1s;
    EXPECT_TRUE(sim.receive(apt::mot_move_absolute(6144000), t1).empty());
    EXPECT_TRUE(sim.poll(t1 + 4400ms).empty());
    EXPECT_NEAR(sim.angle_deg(t1 + 2250ms), 22.5, 0.1);  // halfway in time, halfway in angle
    const auto done = sim.poll(t1 + 4505ms);
    const auto d = apt::decode(done);
    ASSERT_EQ(d.status, apt::DecodeStatus::Complete);
    EXPECT_EQ(d.message.id, apt::kMotMoveCompleted);
    EXPECT_EQ(apt::parse_status_update(d.message)->position, 6144000);
}

}  // namespace
}  // namespace tirpol::acquisition
