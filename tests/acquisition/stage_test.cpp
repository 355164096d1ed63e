// Rotation stages driven through the real serial-port code (termios on a pseudo-terminal) against
// the stage simulator, which speaks the APT binary and Elliptec ASCII protocols byte for byte:
// identification, homing before the first absolute move, the 0/45/90/135° plan, angle wrapping,
// and each injected fault mapped to its DeviceError.

#include "tirpol/acquisition/stage.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <thread>

#include "test_support.h"
#include "tirpol/acquisition/internal/sim_stage.h"
#include "tirpol/acquisition/sim/stage_simulator.h"

namespace tirpol::acquisition {
namespace {

using namespace std::chrono_literals;

/// The simulator engine on a thread, serving a fresh pseudo-terminal.
class SimulatorThread {
public:
    explicit SimulatorThread(StageSimulatorOptions options)
        : m_simulator(options), m_pty(PseudoTerminal::open().value_or_throw()) {
        m_thread = std::thread([this] { serve_stage_simulator(m_simulator, m_pty, m_stop); });
    }
    ~SimulatorThread() {
        m_stop = true;
        m_thread.join();
    }
    const std::string& path() const { return m_path_copy = m_pty.slave_path(), m_path_copy; }

private:
    StageSimulator m_simulator;
    PseudoTerminal m_pty;
    std::atomic<bool> m_stop{false};
    std::thread m_thread;
    mutable std::string m_path_copy;
};

StageSimulatorOptions sim_options(SimProtocol protocol, SimFault fault = SimFault::None) {
    StageSimulatorOptions o;
    o.protocol = protocol;
    o.fault = fault;
    o.deg_per_s = 3600.0;  // fast enough for a quick test, still a real delay per move
    return o;
}

std::string uri_for(SimProtocol protocol, const std::string& path) {
    return (protocol == SimProtocol::Apt ? "thorlabs-apt://" : "elliptec://") + path +
           "?timeout_ms=500";
}

class StageOverPty : public ::testing::TestWithParam<SimProtocol> {};

TEST_P(StageOverPty, IdentifiesHomesAndRunsTheFourAnglePlan) {
    SimulatorThread sim(sim_options(GetParam()));
    auto stage = open_stage(uri_for(GetParam(), sim.path())).value_or_throw();
    const StageInfo info = stage->info();
    if (GetParam() == SimProtocol::Apt) {
        EXPECT_EQ(info.model, "K10CR1");
        EXPECT_EQ(info.serial, "55000123");
        EXPECT_EQ(info.firmware, "3.0.10");
        EXPECT_DOUBLE_EQ(info.counts_per_degree, 409600.0 / 3.0);
    } else {
        EXPECT_EQ(info.model, "ELL14");
        EXPECT_EQ(info.serial, "11400123");
        EXPECT_DOUBLE_EQ(info.counts_per_degree, 143360.0 / 360.0);  // read from the IN reply
    }
    EXPECT_FALSE(stage->is_homed());
    auto refused = stage->move_absolute(45.0, 2s);
    ASSERT_FALSE(refused);
    EXPECT_EQ(refused.error().code, DeviceErrorCode::InvalidArgument);
    EXPECT_NE(refused.error().message.find("home"), std::string::npos);

    ASSERT_TRUE(stage->home(5s)) << stage->home(5s).error().message;
    EXPECT_TRUE(stage->is_homed());
    EXPECT_NEAR(stage->position_deg().value(), 0.0, 1e-9);
    const double resolution = 1.0 / info.counts_per_degree;
    for (double angle : {0.0, 45.0, 90.0, 135.0}) {
        const auto moved = stage->move_absolute(angle, 5s);
        ASSERT_TRUE(moved) << moved.error().message;
        EXPECT_NEAR(stage->position_deg().value(), angle, resolution) << angle;
    }
    // Angles wrap to [0, 360).
    ASSERT_TRUE(stage->move_absolute(370.0, 5s));
    EXPECT_NEAR(stage->position_deg().value(), 10.0, resolution);
    ASSERT_TRUE(stage->move_absolute(-45.0, 5s));
    EXPECT_NEAR(stage->position_deg().value(), 315.0, resolution);
}

struct FaultCase {
    SimProtocol protocol;
    SimFault fault;
    DeviceErrorCode expected;
    const char* message_part;
};

void PrintTo(const FaultCase& c, std::ostream* os) { *os << c.message_part; }

class StageFault : public ::testing::TestWithParam<FaultCase> {};

TEST_P(StageFault, GivesTheRightDeviceError) {
    const FaultCase c = GetParam();
    auto options = sim_options(c.protocol, c.fault);
    options.deg_per_s = 400.0;  // a 90° move takes 225 ms, so a disconnect lands mid-move
    SimulatorThread sim(options);
    auto stage = open_stage(uri_for(c.protocol, sim.path())).value_or_throw();
    ASSERT_TRUE(stage->home(5s));
    const auto moved = stage->move_absolute(90.0, 600ms);
    ASSERT_FALSE(moved);
    EXPECT_EQ(moved.error().code, c.expected) << moved.error().message;
    EXPECT_NE(moved.error().message.find(c.message_part), std::string::npos)
        << moved.error().message;
}

std::string protocol_name(const ::testing::TestParamInfo<SimProtocol>& p) {
    return p.param == SimProtocol::Apt ? "Apt" : "Elliptec";
}

std::string fault_name(const ::testing::TestParamInfo<FaultCase>& p) {
    static const char* const kNames[] = {"None", "NoReply", "Busy", "Error", "Disconnect"};
    return std::string(p.param.protocol == SimProtocol::Apt ? "Apt" : "Elliptec") +
           kNames[static_cast<int>(p.param.fault)];
}

INSTANTIATE_TEST_SUITE_P(Protocols, StageOverPty,
                         ::testing::Values(SimProtocol::Apt, SimProtocol::Elliptec), protocol_name);

INSTANTIATE_TEST_SUITE_P(
    Faults, StageFault,
    ::testing::Values(
        FaultCase{SimProtocol::Apt, SimFault::NoReply, DeviceErrorCode::Timeout, "does not answer"},
        FaultCase{SimProtocol::Apt, SimFault::Busy, DeviceErrorCode::Timeout, "still moving"},
        FaultCase{SimProtocol::Apt, SimFault::Error, DeviceErrorCode::DeviceFault,
                  "position error limit"},
        FaultCase{SimProtocol::Apt, SimFault::DisconnectMidMove, DeviceErrorCode::Disconnected,
                  "hung up"},
        FaultCase{SimProtocol::Elliptec, SimFault::NoReply, DeviceErrorCode::Timeout, "no reply"},
        FaultCase{SimProtocol::Elliptec, SimFault::Busy, DeviceErrorCode::Timeout, "Busy"},
        FaultCase{SimProtocol::Elliptec, SimFault::Error, DeviceErrorCode::DeviceFault,
                  "Mechanical time out"},
        FaultCase{SimProtocol::Elliptec, SimFault::DisconnectMidMove, DeviceErrorCode::Disconnected,
                  "hung up"}),
    fault_name);

TEST(StageSimulatorProcess, ExecutableServesAStageOnItsLink) {
    test::TempDir tmp;
    const auto link = tmp / "ell14";
    int out[2];
    ASSERT_EQ(::pipe(out), 0);
    const pid_t pid = ::fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
        ::dup2(out[1], STDOUT_FILENO);
        ::close(out[0]);
        ::execl(TIRPOL_STAGE_SIM_PATH, "tirpol-stage-sim", "--protocol", "elliptec", "--link",
                link.c_str(), "--move-deg-per-s", "3600", static_cast<char*>(nullptr));
        ::_exit(127);
    }
    ::close(out[1]);
    std::string first_line;
    char c;
    while (::read(out[0], &c, 1) == 1 && c != '\n') first_line.push_back(c);
    ::close(out[0]);
    EXPECT_EQ(first_line.rfind("/dev/pts/", 0), 0u) << first_line;
    {
        auto stage = open_stage("elliptec://" + link.string() + "?address=0").value_or_throw();
        ASSERT_TRUE(stage->home(5s));
        ASSERT_TRUE(stage->move_absolute(135.0, 5s));
        EXPECT_NEAR(stage->position_deg().value(), 135.0, 1.0 / stage->info().counts_per_degree);
    }
    ::kill(pid, SIGTERM);
    int status = 0;
    ::waitpid(pid, &status, 0);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    EXPECT_FALSE(
        std::filesystem::exists(std::filesystem::symlink_status(link)));  // link removed on exit
}

TEST(StageRegistry, RejectsUnknownSchemesAndOptionsByName) {
    auto unknown = open_stage("newport://x");
    ASSERT_FALSE(unknown);
    EXPECT_NE(unknown.error().message.find("unknown stage scheme 'newport'"), std::string::npos);
    auto bad_key = open_stage("sim://?speed=3");
    ASSERT_FALSE(bad_key);
    EXPECT_NE(bad_key.error().message.find("unknown option 'speed'"), std::string::npos);
    auto missing = open_stage("elliptec:///dev/does-not-exist");
    ASSERT_FALSE(missing);
    EXPECT_EQ(missing.error().code, DeviceErrorCode::Disconnected);
}

TEST(SimulatedStage, HomesMovesWrapsAndFailsOnRequest) {
    auto stage = open_stage("sim://?start_deg=12&fail_on_move=3").value_or_throw();
    EXPECT_FALSE(stage->move_absolute(10, 1s));
    ASSERT_TRUE(stage->home(1s));
    ASSERT_TRUE(stage->move_absolute(405, 1s));
    EXPECT_NEAR(stage->position_deg().value(), 45.0, 1e-5);
    ASSERT_TRUE(stage->move_absolute(90, 1s));
    const auto failed = stage->move_absolute(135, 1s);
    ASSERT_FALSE(failed);
    EXPECT_EQ(failed.error().code, DeviceErrorCode::DeviceFault);
}

}  // namespace
}  // namespace tirpol::acquisition
