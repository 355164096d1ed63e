// The same sweep under `mpirun -np 2` (Open MPI, loopback only) and in one process gives bitwise
// the same images and statistics: seeds come from the point index, the renderer is thread-count
// independent. mpirun missing is a failure, not a skip (openmpi-bin is in ./run's PACKAGES).

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <set>

#include "../apps/cli_runner.h"
#include "sweep_test_support.h"
#include "tirpol/core/atomic_file.h"

namespace tirpol::sweep {
namespace {

using tirpol::test::run_cli;
using tirpol::test::run_command;
using tirpol::test::TempDir;

std::string mpirun_command(int ranks) {
    // As root Open MPI needs --allow-run-as-root; loopback only (containers without a network),
    // vader shared memory without the kernel's single-copy mechanism (not permitted in containers).
    return fmt::format(
        "OMPI_MCA_btl_vader_single_copy_mechanism=none {} --allow-run-as-root --oversubscribe "
        "--mca btl self,vader "
        "--mca oob_tcp_if_include lo -np {}",
        TIRPOL_MPIEXEC, ranks);
}

TEST(SweepMpi, TwoRanksGiveBitwiseTheSameResultsAsOneProcess) {
    ASSERT_TRUE(std::filesystem::path(TIRPOL_MPIEXEC).is_absolute() &&
                std::filesystem::exists(TIRPOL_MPIEXEC))
        << "mpirun not found (CMake's MPIEXEC_EXECUTABLE = '" << TIRPOL_MPIEXEC
        << "'): install openmpi-bin";
    TempDir dir;
    // Uneven point costs (2 and 8 samples per pixel), so the dynamic distribution matters.
    const auto sweep = test::write_small_sweep(dir, R"(axes:
  sampling.spp: [2, 8]
  camera.fov_deg: [18, 24, 30]
contrasts:
  ball_vs_snow: {a: ball, b: snow}
)");
    const auto one = dir / "one", two = dir / "two";
    const auto single =
        run_cli(fmt::format("sweep {} -o {} --threads 2 -q", sweep.string(), one.string()));
    ASSERT_EQ(single.exit_code, 0) << single.out;
    const auto mpi =
        run_command(fmt::format("{} {} sweep {} -o {} --threads 1 -q", mpirun_command(2),
                                TIRPOL_CLI_PATH, sweep.string(), two.string()));
    ASSERT_EQ(mpi.exit_code, 0) << mpi.out;
    EXPECT_NE(mpi.out.find("on 2 rank(s) × 1 thread(s)"), std::string::npos) << mpi.out;

    const auto m1 = nlohmann::json::parse(read_file(one / "manifest.json"));
    const auto m2 = nlohmann::json::parse(read_file(two / "manifest.json"));
    EXPECT_EQ(m1["ranks"], 1);
    EXPECT_EQ(m2["ranks"], 2);
    ASSERT_EQ(m2["points"].size(), 6u);
    std::set<int> ranks_used;
    for (std::size_t i = 0; i < 6; ++i) {
        const std::string id = m2["points"][i]["id"];
        EXPECT_EQ(m2["points"][i]["status"], "rendered");
        ranks_used.insert(m2["points"][i]["rank"].get<int>());
        EXPECT_EQ(m1["points"][i]["seed"], m2["points"][i]["seed"]);
        for (const char* file : {"stokes.exr", "statistics.json"})
            EXPECT_TRUE(read_file(one / "points" / id / file) ==
                        read_file(two / "points" / id / file))
                << id << "/" << file << " differs between 1 and 2 ranks";
    }
    EXPECT_EQ(ranks_used.size(), 2u) << "both ranks should have rendered points";
    EXPECT_EQ(read_file(one / "results.csv"), read_file(two / "results.csv"));
    EXPECT_EQ(read_file(one / "results.json"), read_file(two / "results.json"));
}

}  // namespace
}  // namespace tirpol::sweep
