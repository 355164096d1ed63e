#include "tirpol/sweep/sweep_run.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <optional>
#include <string>
#include <thread>

#include "manifest.h"
#include "mpi_dispatch.h"
#include "point_render.h"
#include "sweep_results.h"
#include "tirpol/core/error.h"
#include "tirpol/core/output_guard.h"

namespace tirpol::sweep {

namespace {

void count(SweepSummary& summary) {
    summary.rendered = summary.resumed = summary.failed = 0;
    for (const auto& r : summary.points) {
        summary.rendered += r.status == "rendered";
        summary.resumed += r.status == "resumed";
        summary.failed += r.status == "failed";
    }
}

/// Point folders that killed runs left half written (render_point's ".<id>.partial-<pid>"): with
/// the folder lock held, no other run is writing them.
void remove_abandoned_partial_points(const std::filesystem::path& out_dir) {
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(out_dir / "points", ec)) {
        const std::string name = entry.path().filename().string();
        if (name.size() > 1 && name.front() == '.' && name.find(".partial-") != std::string::npos) {
            std::error_code ignored;
            std::filesystem::remove_all(entry.path(), ignored);
        }
    }
}

}  // namespace

SweepSummary run_sweep(const SweepSpec& spec, const std::filesystem::path& out_dir,
                       const RunOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    const auto points = sweep_points(spec);
    const auto manifest = out_dir / "manifest.json";
    // Every rank checks the folder before any rank writes to it, so all agree (and fail alike).
    const bool exists = std::filesystem::exists(manifest);
    if (exists && !options.resume)
        fail(
            "{} holds a sweep already: pass --resume to continue it, or choose another output "
            "folder",
            out_dir.string());
    if (exists) detail::check_same_sweep(manifest, spec, points);

    detail::MpiSession mpi;
    // One run per folder: rank 0 holds OUT/.lock until the sweep ends; every rank learns whether it
    // got it.
    std::optional<FolderLock> lock;
    std::string lock_error;
    if (mpi.rank() == 0) {
        try {
            lock.emplace(out_dir, "a tirpol sweep");
            remove_abandoned_partial_points(out_dir);
        } catch (const Error& e) {
            lock_error = e.what();
        }
    }
    if (!mpi.broadcast_from_root(lock_error.empty()))
        fail("{}", lock_error.empty()
                       ? out_dir.string() + ": rank 0 could not lock the sweep folder"
                       : lock_error);
    SweepSummary summary;
    summary.is_root = mpi.rank() == 0;
    summary.ranks = mpi.size();
    summary.threads = options.threads > 0
                          ? options.threads
                          : std::max(1, static_cast<int>(std::thread::hardware_concurrency()) /
                                            detail::MpiSession::local_ranks());
    std::vector<std::size_t> pending;
    summary.points.resize(points.size());
    for (const auto& p : points) {
        summary.points[p.index].point = p;
        if (auto done = detail::finished_point(out_dir, p)) {
            summary.points[p.index].status = "resumed";
            summary.points[p.index].statistics = std::move(done);
        } else {
            pending.push_back(p.index);
        }
    }
    mpi.barrier();
    if (summary.is_root) {
        std::filesystem::create_directories(out_dir / "points");
        count(summary);
        detail::write_manifest(manifest, spec, summary);
    }
    mpi.barrier();

    std::size_t finished = points.size() - pending.size();
    const auto on_done = [&](const PointRecord& r) {
        ++finished;
        if (options.progress || r.status == "failed")
            std::fprintf(stderr, "[%zu/%zu] %s %s in %.2f s (rank %d)%s%s\n", finished,
                         points.size(), r.point.id.c_str(), r.status.c_str(), r.seconds, r.rank,
                         r.error.empty() ? "" : ": ", r.error.c_str());
    };
    const auto job = [&](std::size_t index) {
        return detail::render_point(spec, points[index], out_dir, summary.threads);
    };
    for (auto& r : detail::dispatch_points(mpi, pending, points, spec, job, on_done))
        summary.points[r.point.index] = std::move(r);
    if (!summary.is_root) {
        summary.points.clear();
        return summary;
    }
    count(summary);
    summary.wall_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    detail::write_manifest(manifest, spec, summary);
    summary.outputs.push_back(manifest);
    const auto results = write_results(spec, out_dir, summary.points);
    summary.outputs.insert(summary.outputs.end(), results.begin(), results.end());
    return summary;
}

}  // namespace tirpol::sweep
