// Inputs are read only from regular files and never past their limit (limits.h): a FIFO would block
// for ever, /dev/zero never ends (a session.json that was /dev/zero was read to 1 GiB). And the
// memory check that refuses a job before it allocates.

#include <fcntl.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <functional>
#include <future>
#include <numbers>

#include "error_of.h"
#include "test_support.h"
#include "tirpol/core/atomic_file.h"
#include "tirpol/core/config.h"
#include "tirpol/core/error.h"
#include "tirpol/core/limits.h"
#include "tirpol/core/output_guard.h"
#include "tirpol/core/radiometry.h"

using tirpol::test::error_of;

namespace tirpol {
namespace {

TEST(InputFile, DevicesDirectoriesAndMissingFilesAreNamedAsSuch) {
    EXPECT_THAT(error_of([] { (void)read_file("/dev/zero"); }),
                testing::AllOf(testing::HasSubstr("/dev/zero: is a character device"),
                               testing::HasSubstr("only from regular files")));
    const test::TempDir dir;
    EXPECT_THAT(error_of([&] { (void)read_file(dir.path()); }),
                testing::HasSubstr("is a directory"));
    EXPECT_THAT(
        error_of([&] { (void)read_file(dir / "absent.json"); }),
        testing::AllOf(testing::HasSubstr("absent.json"), testing::HasSubstr("no such file")));
    // A symbolic link to a device is the device (how the report's session.json was made).
    std::filesystem::create_symlink("/dev/zero", dir / "session.json");
    EXPECT_THAT(error_of([&] { check_input_file(dir / "session.json"); }),
                testing::HasSubstr("character device"));
    EXPECT_THAT(error_of([&] { (void)ConfigNode::load_file(dir / "session.json"); }),
                testing::HasSubstr("character device"));
}

TEST(InputFile, AFifoIsRefusedWithoutBlocking) {
    const test::TempDir dir;
    const auto fifo = dir / "plan.yaml";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    // With no writer, a blocking open() of a FIFO never returns; run the reads on another thread so
    // a regression fails this test instead of hanging the suite.
    auto reading =
        std::async(std::launch::async, [&] { return error_of([&] { (void)read_file(fifo); }); });
    ASSERT_EQ(reading.wait_for(std::chrono::seconds(20)), std::future_status::ready)
        << "read_file blocked on a FIFO";
    EXPECT_THAT(reading.get(), testing::HasSubstr("plan.yaml: is a FIFO (named pipe)"));
    EXPECT_THAT(error_of([&] { SpectralResponse::load_csv(fifo); }),
                testing::HasSubstr("is a FIFO"));
    if (::access(fifo.c_str(), F_OK) == 0) {
        // Unblock a reader left behind by a failed expectation above, so the process can end.
        const int fd = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
        if (fd >= 0) ::close(fd);
    }
}

TEST(InputFile, SizeIsCheckedBeforeReadingAndTheReadStopsAtTheLimit) {
    const test::TempDir dir;
    test::write_text(dir / "big.csv", std::string(5000, 'x'));
    EXPECT_EQ(read_input_file(dir / "big.csv", 5000).size(), 5000u);
    EXPECT_THAT(
        error_of([&] { (void)read_input_file(dir / "big.csv", 4999); }),
        testing::AllOf(testing::HasSubstr("big.csv: 5000 bytes is larger than the 4999 bytes")));
    EXPECT_EQ(read_file(dir / "big.csv"), std::string(5000, 'x'));
}

TEST(InputFile, InvalidUtf8InYamlIsNamedWithFileLineAndColumn) {
    const test::TempDir dir;
    test::write_text(dir / "plan.yaml", "name: ok\nnote: caf\xe9 au lait\n");
    EXPECT_THAT(error_of([&] { (void)ConfigNode::load_file(dir / "plan.yaml"); }),
                testing::HasSubstr("plan.yaml:2:10: invalid UTF-8 (byte 0xE9)"));
    EXPECT_EQ(first_invalid_utf8("ok \xc3\xa9 \xff"), 6u);  // é is valid, 0xFF never is
    EXPECT_EQ(first_invalid_utf8("µm, °C, σ"), std::string_view::npos);
}

TEST(MemoryBudget, AJobBeyondTheAvailableMemoryIsRefusedWithItsEstimate) {
    constexpr std::uint64_t GiB = std::uint64_t{1} << 30;
    // 8 GiB available: 80 % (limits::kMaxMemoryFraction) is the budget.
    EXPECT_NO_THROW(check_memory_estimate(6 * GiB, "render", 8 * GiB));
    EXPECT_THAT(
        error_of([&] { check_memory_estimate(7 * GiB, "render of 2×2 pixels", 8 * GiB); }),
        testing::AllOf(testing::HasSubstr("render of 2×2 pixels: needs an estimated 7.00 GiB"),
                       testing::HasSubstr("6.40 GiB this machine has available")));
    EXPECT_NO_THROW(
        check_memory_estimate(1000 * GiB, "anything", std::nullopt));  // not Linux: no check
    // This machine's /proc/meminfo is read (Linux: MemAvailable is there since 3.14).
    const auto available = available_memory_bytes();
    ASSERT_TRUE(available.has_value());
    EXPECT_GT(*available, 0u);
}

TEST(BandLimits, EdgesOutsideTheTableAndOversizedGridsAreRefusedBeforeAllocating) {
    // planck --band-um 0.001 1e7 built 4.2 GB of nodes, then bad_alloc; 1 1e300 printed 0.
    EXPECT_THAT(error_of([] { Band(0.001, 1e7); }),
                testing::HasSubstr("expected 0.1 ≤ lo < hi ≤ 1000"));
    EXPECT_THAT(error_of([] { Band(1.0, 1e300); }),
                testing::HasSubstr("expected 0.1 ≤ lo < hi ≤ 1000"));
    EXPECT_THAT(error_of([] { Band(std::nan(""), 14.0); }),
                testing::HasSubstr("expected 0.1 ≤ lo"));
    // The whole table range integrates (≈ 64 000 nodes at 0.25 µm panels) and Planck's total is
    // there: σT⁴/π at 300 K is 146.2 W/(m²·sr) (Stefan–Boltzmann, CODATA 2018 σ); 0.1–1000 µm
    // misses only the Rayleigh–Jeans tail beyond 1 mm, (15/π⁴)·x³/3 with x = c2/(λT) = 0.048: 6e-6
    // of it.
    const Band whole(0.1, 1000.0);
    EXPECT_NEAR(whole.radiance(300.0), 5.670374419e-8 * std::pow(300.0, 4) / std::numbers::pi,
                2e-3);
    // A grid finer than the node limit is refused with the count, not allocated.
    EXPECT_THAT(
        error_of([] { Band(0.1, 1000.0, std::nullopt, 1e-4); }),
        testing::AllOf(testing::HasSubstr("quadrature panels"), testing::HasSubstr("1048576")));
}

}  // namespace
}  // namespace tirpol
