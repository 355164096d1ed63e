#pragma once
/// \file sweep_run.h
/// Running a sweep: every point rendered into OUT/points/<id>/ (stokes.exr with its PNG quicklooks,
/// pol<angle>.exr with a sensor model, statistics.json), each folder written under a temporary name
/// and renamed when complete, so a folder that exists is a finished point. OUT/manifest.json
/// records each point's parameters, seed, status and error; a failing point is recorded and the
/// sweep goes on.
///
/// Without mpirun the points are rendered one after the other, each with the renderer's threads.
/// Under `mpirun -np N` (Open MPI) rank 0 hands out point indices on request (dynamic: uneven point
/// costs balance themselves) and renders points itself on a second thread; every rank writes its
/// own points; rank 0 gathers the records, writes the manifest and the results. Images do not
/// depend on the number of ranks or threads: each point's seed comes from its index (point_seed)
/// and the renderer's output is thread-count independent (counter-based random numbers,
/// renderer.h).

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "tirpol/sweep/point_statistics.h"
#include "tirpol/sweep/sweep_file.h"

namespace tirpol::sweep {

struct RunOptions {
    int threads = 0;        ///< renderer threads per rank; 0: this machine's cores / ranks on it
    bool resume = false;    ///< continue a sweep in OUT: finished points are not rendered again
    bool progress = false;  ///< one line per finished point on stderr (rank 0)
};

/// What happened to one point.
struct PointRecord {
    SweepPoint point;
    std::string status =
        "pending";      ///< "rendered", "resumed" (finished by an earlier run), "failed", "pending"
    std::string error;  ///< why it failed
    int rank = 0;       ///< MPI rank that rendered it
    double seconds = 0.0;         ///< loading, thermal model, render and writing
    double render_seconds = 0.0;  ///< of which the renderer (the part that uses the threads)
    double wait_seconds = 0.0;    ///< time its rank waited for the assignment (scheduling overhead)
    std::optional<PointStatistics> statistics;
};

struct SweepSummary {
    bool is_root = true;  ///< false on MPI ranks other than 0 (they hold no records)
    int ranks = 1;
    int threads = 1;  ///< renderer threads per rank
    std::vector<PointRecord> points;
    std::size_t rendered = 0, resumed = 0, failed = 0;
    double wall_seconds = 0.0;
    std::vector<std::filesystem::path> outputs;  ///< manifest and results written by rank 0
};

/// Runs the sweep into `out_dir` (see above) and, on rank 0, writes the manifest and the results
/// (sweep_results.h). Throws tirpol::Error if `out_dir` holds a sweep and `resume` is off, or if it
/// holds a different sweep (other points or parameters) and `resume` is on.
SweepSummary run_sweep(const SweepSpec& spec, const std::filesystem::path& out_dir,
                       const RunOptions& options);

/// The outputs `run_sweep` claims in its folder (OutputGuard patterns): the manifest, the results,
/// the contact sheets and the points', plots', tiles' and animation folders.
const std::vector<std::string>& sweep_output_patterns();

/// What `tirpol sweep` prints on rank 0: points, ranks, threads, time, how many were rendered,
/// resumed and failed, the files written directly in `out_dir`, and each failed point with its
/// error. `sweep_name` names the sweep file.
std::string sweep_summary_text(const SweepSummary& summary, const std::string& sweep_name,
                               const std::filesystem::path& out_dir);

}  // namespace tirpol::sweep
