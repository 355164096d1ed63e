// The blackbody controller path: the Fluke 4180 driver (real serial-port code) against the
// simulator on a pseudo-terminal, the simulator's physics (first-order response, the STABLE LIMIT
// flag), the wait for a set-point, faults as values, and the tirpol-blackbody-sim program.

#include "tirpol/acquisition/blackbody.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <thread>

#include "child_process.h"
#include "pty_device_thread.h"
#include "test_support.h"
#include "tirpol/acquisition/internal/blackbody_simulator.h"
#include "tirpol/acquisition/internal/blackbody_wait.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/session.h"

namespace tirpol::acquisition {
namespace {

using namespace std::chrono_literals;
using ::testing::HasSubstr;
using Clock = PtyDevice::Clock;
using SimThread = test::PtyDeviceThread<BlackbodySimulator>;

std::string exchange(BlackbodySimulator& sim, const std::string& command, Clock::time_point now) {
    const auto out =
        sim.receive({reinterpret_cast<const std::uint8_t*>(command.data()), command.size()}, now);
    return {out.begin(), out.end()};
}

BlackbodySimulatorOptions fast_options() {
    BlackbodySimulatorOptions o;
    o.time_constant_s = 0.4;
    o.noise_k = 0.002;
    o.stability_limit_k = 0.02;
    o.stability_window_s = 0.3;
    o.sample_period_s = 0.02;
    return o;
}

/// The driver on the simulator's pty; the reply timeout is generous for a loaded machine unless
/// given.
std::unique_ptr<BlackbodyController> open_on(const SimThread& sim,
                                             const std::string& query = "?timeout_ms=5000") {
    return open_blackbody("fluke-4180://" + sim.path() + query).value_or_throw();
}

TEST(BlackbodySimulator, PlateFollowsAFirstOrderResponse) {
    // T(t) = T_set + (T_0 − T_set)·e^(−t/τ): 63.2 % of a step after τ, 95.0 % after 3τ.
    BlackbodySimulatorOptions o;
    o.time_constant_s = 60.0;
    const auto t0 = Clock::now();
    BlackbodySimulator sim(o, t0);
    EXPECT_EQ(exchange(sim, "SOUR:SPO 43.0\n", t0), "");
    const double step = 43.0 + 273.15 - o.ambient_k;
    EXPECT_NEAR(sim.plate_temperature_k(t0 + 60s) - o.ambient_k, step * (1 - std::exp(-1.0)), 1e-9);
    EXPECT_NEAR(sim.plate_temperature_k(t0 + 180s) - o.ambient_k, step * (1 - std::exp(-3.0)),
                1e-9);
    // A new set-point starts from where the plate is, not from the old target.
    const double at_30s = sim.plate_temperature_k(t0 + 30s);
    exchange(sim, "SOUR:SPO 23.0\n", t0 + 30s);
    EXPECT_NEAR(sim.plate_temperature_k(t0 + 30s), at_30s, 1e-9);
    EXPECT_LT(sim.plate_temperature_k(t0 + 40s), at_30s);
}

TEST(BlackbodySimulator, StabilityFlagNeedsAFullWindowWithinTheLimit) {
    BlackbodySimulatorOptions o;
    o.time_constant_s = 10.0;
    o.noise_k = 0.0;
    o.stability_limit_k = 0.05;
    o.stability_window_s = 5.0;
    const auto t0 = Clock::now();
    BlackbodySimulator sim(o, t0);
    EXPECT_EQ(exchange(sim, "SOUR:STAB:TEST?\n", t0 + 1s),
              "0\r\n");  // less than a window of readings
    EXPECT_EQ(exchange(sim, "SOUR:STAB:TEST?\n", t0 + 6s), "1\r\n");  // at ambient, constant
    exchange(sim, "SOUR:SPO 33.0\n", t0 + 6s);
    // Over 5 s at t ≈ τ the plate moves ≈ 3 K: far outside ±0.05 K.
    EXPECT_EQ(exchange(sim, "SOUR:STAB:TEST?\n", t0 + 16s), "0\r\n");
    // After 9τ the last window moves by 10 K·(e^(−8.5) − e^(−9)) ≈ 0.8 mK.
    EXPECT_EQ(exchange(sim, "SOUR:STAB:TEST?\n", t0 + 96s), "1\r\n");
    // Tightening the limit below the window's spread clears the flag (SOUR:STAB:LIM).
    exchange(sim, "SOUR:STAB:LIM 0.0001\n", t0 + 96s);
    EXPECT_EQ(exchange(sim, "SOUR:STAB:TEST?\n", t0 + 96s), "0\r\n");
}

TEST(BlackbodySimulator, RefusalsGoToTheErrorQueue) {
    const auto t0 = Clock::now();
    BlackbodySimulator sim(BlackbodySimulatorOptions{}, t0);
    exchange(sim, "SOUR:SPO 130\n", t0);  // a 4180 goes to 120 °C
    exchange(sim, "SOUR:FOO?\n", t0);
    EXPECT_EQ(exchange(sim, "syst:err?\r\n", t0), "-222,\"Data out of range\"\r\n");
    EXPECT_EQ(exchange(sim, "SYSTem:ERRor?\n", t0), "-113,\"Undefined header\"\r\n");
    EXPECT_EQ(exchange(sim, "SYST:ERR?\n", t0), "0,\"No error\"\r\n");
}

TEST(BlackbodyController, DriverSetsReadsAndReachesASetPoint) {
    SimThread sim(fast_options());
    auto bb = open_on(sim);
    const BlackbodyInfo info = bb->info();
    EXPECT_EQ(info.vendor, "FLUKE");
    EXPECT_EQ(info.model, "4180");
    EXPECT_NEAR(info.max_set_point_k, 393.15, 1e-9);

    const BlackbodyStabilityCriterion criterion{0.02, 0.2, 20.0, 0.02};
    const auto reached = bring_blackbody_to(*bb, 308.15, criterion).value_or_throw();
    EXPECT_NEAR(reached.last.temperature_k, 308.15, 0.02);
    EXPECT_NEAR(reached.last.set_point_k, 308.15, 1e-9);
    EXPECT_TRUE(reached.last.stable);
    // The plate needs τ·ln(10 K / 0.02 K) ≈ 2.5 s to come within tolerance, then the flag and the
    // hold.
    EXPECT_GT(reached.wait_s, 0.4 * std::log(12.0 / 0.02));
    EXPECT_NEAR(sim.device().plate_temperature_k(Clock::now()), 308.15, 0.02);
}

TEST(BlackbodyController, OutOfRangeSetPointIsRefusedBeforeSending) {
    SimThread sim(fast_options());
    auto bb = open_on(sim);
    const Status s = bb->set_temperature_k(400.0);
    ASSERT_FALSE(s);
    EXPECT_EQ(s.error().code, DeviceErrorCode::InvalidArgument);
    EXPECT_THAT(s.error().message, HasSubstr("outside the 4180 range 258.15–393.15 K"));
    EXPECT_NEAR(bb->status().value_or_throw().set_point_k, fast_options().ambient_k,
                1e-9);  // nothing was sent
}

TEST(BlackbodyController, FaultsAreValues) {
    auto options = fast_options();
    options.fault_on_set = 2;
    {
        options.fault = BlackbodyFault::OverTemperature;
        SimThread sim(options);
        auto bb = open_on(sim);
        ASSERT_TRUE(bb->set_temperature_k(300.0));
        ASSERT_TRUE(bb->status());
        ASSERT_TRUE(bb->set_temperature_k(310.0));  // the cutout trips: the command was accepted
        const auto s = bb->status();
        ASSERT_FALSE(s);
        EXPECT_EQ(s.error().code, DeviceErrorCode::DeviceFault);
        EXPECT_THAT(s.error().message, HasSubstr("over-temperature cutout has tripped"));
        const auto wait = bring_blackbody_to(*bb, 305.0, {0.05, 0.1, 5.0, 0.02});
        ASSERT_FALSE(wait);
        EXPECT_EQ(wait.error().code, DeviceErrorCode::DeviceFault);
    }
    {
        options.fault = BlackbodyFault::NoReply;
        SimThread sim(options);
        auto bb = open_on(sim, "?timeout_ms=200");
        ASSERT_TRUE(bb->set_temperature_k(300.0));
        const Status s = bb->set_temperature_k(310.0);
        ASSERT_FALSE(s);
        EXPECT_EQ(s.error().code, DeviceErrorCode::Timeout);
        EXPECT_THAT(s.error().message, HasSubstr("no reply to SYST:ERR? within 200 ms"));
    }
    {
        options.fault = BlackbodyFault::Garbled;
        SimThread sim(options);
        auto bb = open_on(sim);
        ASSERT_TRUE(bb->set_temperature_k(300.0));
        const Status s = bb->set_temperature_k(310.0);
        ASSERT_FALSE(s);
        EXPECT_EQ(s.error().code, DeviceErrorCode::BadReply);
        EXPECT_THAT(s.error().message, HasSubstr("reply \""));
    }
}

TEST(BlackbodyController, ASetPointNeverStableTimesOutNamingTheSetPointAndLastReading) {
    auto options = fast_options();
    options.time_constant_s = 30.0;  // far too slow for the timeout below
    SimThread sim(options);
    auto bb = open_on(sim);
    const auto r = bring_blackbody_to(*bb, 318.15, {0.05, 0.2, 0.5, 0.05});
    ASSERT_FALSE(r);
    EXPECT_EQ(r.error().code, DeviceErrorCode::Timeout);
    EXPECT_THAT(
        r.error().message,
        HasSubstr("set-point 318.15 K (45.00 °C) not stable within ±0.05 K for 0.2 s after 0.5 s"));
    EXPECT_THAT(r.error().message, HasSubstr("last reading 29"));  // ≈ 296.5 K: barely moved
}

TEST(BlackbodyController, SimUriServesTheSameProtocolInProcess) {
    auto bb =
        open_blackbody("sim://?tau_s=0.2&window_s=0.2&limit_k=0.02&noise_k=0.001").value_or_throw();
    EXPECT_EQ(bb->info().model, "4180");
    const auto reached = bring_blackbody_to(*bb, 290.0, {0.02, 0.1, 20.0, 0.02}).value_or_throw();
    EXPECT_NEAR(reached.last.temperature_k, 290.0, 0.02);
    const auto bad = open_blackbody("sim://?tau=3");
    ASSERT_FALSE(bad);
    EXPECT_THAT(bad.error().message, HasSubstr("unknown option 'tau'"));
    EXPECT_THAT(open_blackbody("fluke-9999:///dev/ttyUSB0").error().message,
                HasSubstr("unknown blackbody controller type"));
}

TEST(BlackbodyController, ReadingLogSummarisesWithSampleStatistics) {
    BlackbodyReadingLog log(300.0, 12.5);
    for (double t : {299.99, 300.00, 300.01, 300.02}) log.add({t, 300.0, true});
    log.add({300.03, 300.0, false});
    const BlackbodyReadings r = log.summary();
    EXPECT_EQ(r.readings, 5);
    EXPECT_NEAR(r.mean_k, 300.01, 1e-9);
    EXPECT_NEAR(r.std_k, std::sqrt(0.001 / 4.0), 1e-9);  // N − 1
    EXPECT_DOUBLE_EQ(r.min_k, 299.99);
    EXPECT_DOUBLE_EQ(r.max_k, 300.03);
    EXPECT_FALSE(r.stable);
    EXPECT_DOUBLE_EQ(r.wait_s, 12.5);
}

TEST(BlackbodySimulatorProgram, ServesOnAPtyThatTheDriverOpens) {
    test::TempDir tmp;
    const auto link = tmp / "bb";
    test::ChildProcess sim(
        {TIRPOL_BLACKBODY_SIM_PATH, "--link", link.string(), "--tau-s", "0.3", "--window-s", "0.2"},
        tmp / "sim.log");
    for (int i = 0; i < 500 && !std::filesystem::exists(link); ++i)
        std::this_thread::sleep_for(10ms);
    ASSERT_TRUE(std::filesystem::exists(link)) << "tirpol-blackbody-sim did not create its link";
    {
        auto bb =
            open_blackbody("fluke-4180://" + link.string() + "?timeout_ms=5000").value_or_throw();
        EXPECT_EQ(bb->info().vendor, "FLUKE");
        ASSERT_TRUE(bb->set_temperature_k(300.0));
        EXPECT_NEAR(bb->status().value_or_throw().set_point_k, 300.0, 1e-9);
    }
    sim.signal(SIGTERM);
    EXPECT_EQ(sim.wait_for(5s), 0);
    EXPECT_FALSE(std::filesystem::exists(link));
}

/// `tirpol-blackbody-sim` linked at DIR/bb (τ = 0.3 s) with `extra` arguments, waiting for the
/// link.
std::unique_ptr<test::ChildProcess> start_blackbody_sim(const std::filesystem::path& dir,
                                                        std::vector<std::string> extra = {}) {
    std::vector<std::string> args{TIRPOL_BLACKBODY_SIM_PATH,
                                  "--link",
                                  (dir / "bb").string(),
                                  "--tau-s",
                                  "0.3",
                                  "--window-s",
                                  "0.2",
                                  "--limit-k",
                                  "0.02",
                                  "--sample-period-s",
                                  "0.02",
                                  "--noise-k",
                                  "0.002"};
    args.insert(args.end(), extra.begin(), extra.end());
    auto sim = std::make_unique<test::ChildProcess>(args, dir / "bb-sim.log");
    for (int i = 0; i < 500 && !std::filesystem::exists(dir / "bb"); ++i)
        std::this_thread::sleep_for(10ms);
    return sim;
}

int run_acquire(const std::filesystem::path& dir, const char* log) {
    test::ChildProcess acquire(
        {TIRPOL_CLI_PATH, "acquire", (dir / "plan.yaml").string(), "--camera",
         "sim://uniform?width=16&height=12&counts=1200&noise=2&fps=100", "--stage", "sim://",
         "--blackbody", "fluke-4180://" + (dir / "bb").string() + "?timeout_ms=5000", "-o",
         (dir / "session").string(), "--non-interactive"},
        dir / log);
    return acquire.wait_for(120s).value_or(-1);
}

constexpr const char* kControlledPlan = R"(angles_deg: [0]
frames_per_angle: 2
settle_s: 0
references:
  - kind: blackbody
    temperatures_c: [20, 30]
    frames: 4
    angles_deg: [0, 90]
    controller: {tolerance_k: 0.02, stable_for_s: 0.2, timeout_s: 20, poll_s: 0.05}
)";

TEST(AcquireWithBlackbody, RunsTheSetPointsUnattendedAndRecordsTheReadings) {
    test::TempDir tmp;
    test::write_text(tmp / "plan.yaml", kControlledPlan);
    auto sim = start_blackbody_sim(tmp.path());
    ASSERT_EQ(run_acquire(tmp.path(), "acquire.log"), 0) << read_file(tmp / "acquire.log");
    const SessionManifest m = read_session(tmp / "session");
    ASSERT_EQ(m.records.size(), 5u);  // 2 set-points × 2 angles + 1 polarizer step
    ASSERT_TRUE(m.blackbody_controller);
    EXPECT_EQ(m.blackbody_controller->uri,
              "fluke-4180://" + (tmp / "bb").string() + "?timeout_ms=5000");
    const double set_points[] = {293.15, 293.15, 303.15, 303.15};
    for (std::size_t i = 0; i < 4; ++i) {
        const SessionRecord& r = m.records[i];
        ASSERT_TRUE(r.blackbody_readings) << r.file;
        EXPECT_DOUBLE_EQ(r.blackbody_readings->set_point_k, set_points[i]);
        EXPECT_NEAR(*r.blackbody_temperature_k, set_points[i], 0.02);
        EXPECT_EQ(r.angle_deg_requested, i % 2 == 0 ? 0.0 : 90.0);
    }
    EXPECT_EQ(m.records[1].blackbody_readings->wait_s,
              0.0);  // same set-point, next angle: no new wait
    EXPECT_GT(m.records[2].blackbody_readings->wait_s, 0.2);
    EXPECT_EQ(m.records[3].file, "frames/s003_bb_303.15K_pol_090.000deg.exr");
}

TEST(AcquireWithBlackbody, AControllerFaultStopsTheRunNamingTheStep) {
    test::TempDir tmp;
    test::write_text(tmp / "plan.yaml", kControlledPlan);
    auto sim =
        start_blackbody_sim(tmp.path(), {"--fault", "over-temperature", "--fault-on-set", "2"});
    EXPECT_EQ(run_acquire(tmp.path(), "acquire.log"), 1);
    const std::string log = read_file(tmp / "acquire.log");
    EXPECT_THAT(
        log, HasSubstr("step 3/5 (blackbody at 303.15 K, polarizer 0°): blackbody device fault"));
    EXPECT_THAT(log, HasSubstr("over-temperature cutout has tripped"));
    EXPECT_EQ(read_session(tmp / "session").records.size(),
              2u);  // the first set-point's records are kept
}

TEST(AcquireWithBlackbody, APlanWithSetPointsNeedsAController) {
    test::TempDir tmp;
    test::write_text(tmp / "plan.yaml", kControlledPlan);
    test::ChildProcess acquire({TIRPOL_CLI_PATH, "acquire", (tmp / "plan.yaml").string(),
                                "--camera", "sim://uniform?width=8&height=6", "--stage", "sim://",
                                "-o", (tmp / "session").string(), "--non-interactive"},
                               tmp / "acquire.log");
    EXPECT_EQ(acquire.wait_for(60s), 1);
    EXPECT_THAT(read_file(tmp / "acquire.log"),
                HasSubstr("no blackbody controller was given (tirpol acquire --blackbody URI)"));
}

}  // namespace
}  // namespace tirpol::acquisition
