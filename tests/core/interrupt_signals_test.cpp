// Ctrl-C handling written once: the first SIGINT/SIGTERM sets the flag and the process goes on, a
// second ends it with the signal, and the handlers in place before come back afterwards.

#include "tirpol/core/interrupt_signals.h"

#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <thread>

#include "tirpol/core/error.h"

namespace tirpol {
namespace {

std::atomic<int> g_test_handler_calls{0};
extern "C" void count_signal(int) { ++g_test_handler_calls; }

TEST(InterruptSignals, FirstSignalSetsTheFlagAndThePreviousHandlerComesBack) {
    const auto before = std::signal(SIGINT, count_signal);
    {
        InterruptSignals signals;
        EXPECT_FALSE(signals.interrupted());
        std::raise(SIGINT);
        EXPECT_TRUE(signals.interrupted());
        EXPECT_EQ(g_test_handler_calls.load(), 0);
    }
    std::raise(SIGINT);
    EXPECT_EQ(g_test_handler_calls.load(), 1);
    std::signal(SIGINT, before);
}

TEST(InterruptSignals, SigtermCountsAsWellAndANewInstanceStartsClear) {
    {
        InterruptSignals signals;
        std::raise(SIGTERM);
        EXPECT_TRUE(signals.interrupted());
    }
    InterruptSignals again;
    EXPECT_FALSE(again.interrupted());
}

TEST(InterruptSignals, OnlyOneAtATime) {
    InterruptSignals signals;
    EXPECT_THROW(InterruptSignals second, Error);
}

TEST(InterruptSignalsDeathTest, SecondSignalEndsTheProcessWithIt) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    EXPECT_EXIT(
        {
            InterruptSignals signals;
            std::raise(SIGINT);
            std::raise(SIGINT);
            std::exit(0);
        },
        testing::KilledBySignal(SIGINT), "");
}

using namespace std::chrono_literals;

// Polls `done` for up to 5 s (the watcher polls every 10 ms; a loaded machine may be slow).
template <typename Done>
bool eventually(Done done) {
    for (int i = 0; i < 500 && !done(); ++i) std::this_thread::sleep_for(10ms);
    return done();
}

TEST(InterruptWatcher, ActsOnceWhenTheFlagRisesAndNeverBefore) {
    std::atomic<bool> interrupt{false};
    std::atomic<int> calls{0};
    InterruptWatcher watcher(interrupt, [&] { return ++calls, true; }, {});
    std::this_thread::sleep_for(100ms);
    EXPECT_EQ(calls, 0) << "acted without an interruption";
    interrupt = true;  // what the SIGINT handler does
    ASSERT_TRUE(eventually([&] { return calls > 0; }));
    std::this_thread::sleep_for(100ms);
    EXPECT_EQ(calls, 1) << "a zero repeat period acts once";
}

TEST(InterruptWatcher, AsksAgainUntilItActsThenRepeatsAfterThePeriod) {
    std::atomic<bool> interrupt{true};
    std::atomic<bool> ready{false};
    std::atomic<int> asked{0}, acted{0};
    {
        InterruptWatcher watcher(interrupt,
                                 [&] {
                                     ++asked;
                                     if (!ready) return false;  // e.g. the stage is not open yet
                                     ++acted;
                                     return true;
                                 },
                                 {50ms});
        ASSERT_TRUE(eventually([&] { return asked >= 3; }));
        EXPECT_EQ(acted, 0);
        ready = true;
        ASSERT_TRUE(eventually([&] { return acted >= 3; })) << "not repeated every 50 ms";
    }
    const int after = acted;
    std::this_thread::sleep_for(100ms);
    EXPECT_EQ(acted, after) << "acted after it was destroyed";
}

TEST(InterruptWatcher, CallsOnOverdueOnceWhenTheProgramOutlivesTheGrace) {
    std::atomic<bool> interrupt{false};
    std::atomic<int> overdue{0};
    {
        InterruptWatcher watcher(interrupt, [] { return true; }, {0ms, 100ms, [&] { ++overdue; }});
        std::this_thread::sleep_for(200ms);
        EXPECT_EQ(overdue, 0) << "called without an interruption";
        interrupt = true;
        ASSERT_TRUE(eventually([&] { return overdue > 0; }));
        std::this_thread::sleep_for(50ms);
    }
    EXPECT_EQ(overdue, 1);
    // A program that finishes (the watcher is destroyed) within the grace period is left alone.
    overdue = 0;
    {
        InterruptWatcher watcher(interrupt, [] { return true; }, {0ms, 60s, [&] { ++overdue; }});
    }
    EXPECT_EQ(overdue, 0);
}

}  // namespace
}  // namespace tirpol
