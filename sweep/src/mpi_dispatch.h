#pragma once
// Open MPI session and the dynamic distribution of point indices (private to the sweep module).

#include <functional>
#include <optional>
#include <vector>

#include "tirpol/sweep/sweep_run.h"

namespace tirpol::sweep::detail {

/// MPI_Init_thread on construction when the process was started by an MPI launcher (mpirun, srun),
/// MPI_Finalize on destruction; without a launcher the sweep runs as one rank without MPI.
class MpiSession {
public:
    MpiSession();
    ~MpiSession();
    MpiSession(const MpiSession&) = delete;
    MpiSession& operator=(const MpiSession&) = delete;
    bool active() const { return m_active; }
    int rank() const { return m_rank; }
    int size() const { return m_size; }
    /// Waits for every rank (no-op without MPI).
    void barrier() const;
    /// Rank 0's `value`, on every rank (`value` itself without MPI).
    bool broadcast_from_root(bool value) const;
    /// Ranks of this job on this machine (threads default to cores / local ranks).
    static int local_ranks();

private:
    bool m_active = false;
    int m_rank = 0, m_size = 1;
};

/// Renders one point (index into the sweep's points) and returns its record.
using PointJob = std::function<PointRecord(std::size_t index)>;

/// Rank 0: hands out `pending` indices in order to whichever rank asks, renders points itself on a
/// second thread, and returns every record it received or made (by index). Other ranks: ask,
/// render, report, until told to stop; return nothing. Only the calling thread uses MPI
/// (MPI_THREAD_FUNNELED).
std::vector<PointRecord> dispatch_points(const MpiSession& mpi,
                                         const std::vector<std::size_t>& pending,
                                         const std::vector<SweepPoint>& points,
                                         const SweepSpec& spec, const PointJob& job,
                                         const std::function<void(const PointRecord&)>& on_done);

}  // namespace tirpol::sweep::detail
