// Ctrl-C handling written once: the first SIGINT/SIGTERM sets the flag and the process goes on, a
// second ends it with the signal, and the handlers in place before come back afterwards.

#include "tirpol/core/interrupt_signals.h"

#include <gtest/gtest.h>

#include <csignal>

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

}  // namespace
}  // namespace tirpol
