#include "mpi_dispatch.h"

#include <mpi.h>

#include <chrono>
#include <cstdlib>
#include <mutex>
#include <thread>

#include "records_json.h"
#include "tirpol/core/error.h"

namespace tirpol::sweep::detail {

namespace {

constexpr int kTagReport =
    1;  // rank → 0: the record of the last point (empty at first), i.e. "next, please"
constexpr int kTagAssign = 2;  // 0 → rank: a point index, or −1 = no more points

bool launched_by_mpi() {
    for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE", "PMI_RANK"})
        if (std::getenv(name)) return true;
    return false;
}

void check(int code, const char* call) {
    if (code != MPI_SUCCESS) fail("MPI: {} failed (error code {})", call, code);
}

PointRecord worker_record(std::size_t index, const PointJob& job, int rank, double wait_seconds) {
    PointRecord r = job(index);
    r.rank = rank;
    r.wait_seconds = wait_seconds;
    return r;
}

}  // namespace

MpiSession::MpiSession() {
    if (!launched_by_mpi()) return;
    int provided = 0;
    check(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
    m_active = true;
    MPI_Comm_rank(MPI_COMM_WORLD, &m_rank);
    MPI_Comm_size(MPI_COMM_WORLD, &m_size);
}

MpiSession::~MpiSession() {
    if (m_active) MPI_Finalize();
}

void MpiSession::barrier() const {
    if (m_active) check(MPI_Barrier(MPI_COMM_WORLD), "MPI_Barrier");
}

bool MpiSession::broadcast_from_root(bool value) const {
    if (!m_active) return value;
    int flag = value ? 1 : 0;
    check(MPI_Bcast(&flag, 1, MPI_INT, 0, MPI_COMM_WORLD), "MPI_Bcast");
    return flag != 0;
}

int MpiSession::local_ranks() {
    for (const char* name : {"OMPI_COMM_WORLD_LOCAL_SIZE", "SLURM_NTASKS_PER_NODE"})
        if (const char* v = std::getenv(name)) return std::max(1, std::atoi(v));
    return 1;
}

std::vector<PointRecord> dispatch_points(const MpiSession& mpi,
                                         const std::vector<std::size_t>& pending,
                                         const std::vector<SweepPoint>& points,
                                         const SweepSpec& spec, const PointJob& job,
                                         const std::function<void(const PointRecord&)>& on_done) {
    std::vector<PointRecord> records;
    if (!mpi.active() || mpi.size() == 1) {
        for (std::size_t index : pending) {
            records.push_back(worker_record(index, job, 0, 0.0));
            on_done(records.back());
        }
        return records;
    }
    if (mpi.rank() != 0) {
        std::string report;
        while (true) {
            const auto asked = std::chrono::steady_clock::now();
            check(MPI_Send(report.data(), static_cast<int>(report.size()), MPI_CHAR, 0, kTagReport,
                           MPI_COMM_WORLD),
                  "MPI_Send");
            long long index = -1;
            check(MPI_Recv(&index, 1, MPI_LONG_LONG, 0, kTagAssign, MPI_COMM_WORLD,
                           MPI_STATUS_IGNORE),
                  "MPI_Recv");
            if (index < 0) return records;
            const double wait =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - asked).count();
            report = record_json(spec, worker_record(static_cast<std::size_t>(index), job,
                                                     mpi.rank(), wait))
                         .dump();
        }
    }

    std::mutex mutex;
    std::size_t next = 0;
    const auto take = [&]() -> long long {
        std::lock_guard lock(mutex);
        return next < pending.size() ? static_cast<long long>(pending[next++]) : -1;
    };
    const auto keep = [&](PointRecord r) {
        std::lock_guard lock(mutex);
        on_done(r);
        records.push_back(std::move(r));
    };
    // Rank 0 renders too; its own points need no message, so their wait is the lock only.
    std::thread local([&] {
        for (long long index = take(); index >= 0; index = take())
            keep(worker_record(static_cast<std::size_t>(index), job, 0, 0.0));
    });
    int active = mpi.size() - 1;
    std::string buffer;
    while (active > 0) {
        int flag = 0;
        MPI_Status status;
        check(MPI_Iprobe(MPI_ANY_SOURCE, kTagReport, MPI_COMM_WORLD, &flag, &status), "MPI_Iprobe");
        if (!flag) {
            // Polling with a short sleep instead of a blocking receive: Open MPI's blocking calls
            // spin and would take a core from rank 0's own rendering thread.
            std::this_thread::sleep_for(std::chrono::microseconds(200));
            continue;
        }
        int length = 0;
        MPI_Get_count(&status, MPI_CHAR, &length);
        buffer.resize(static_cast<std::size_t>(length));
        check(MPI_Recv(buffer.data(), length, MPI_CHAR, status.MPI_SOURCE, kTagReport,
                       MPI_COMM_WORLD, MPI_STATUS_IGNORE),
              "MPI_Recv");
        if (!buffer.empty()) keep(record_from_json(nlohmann::json::parse(buffer), points));
        long long index = take();
        check(MPI_Send(&index, 1, MPI_LONG_LONG, status.MPI_SOURCE, kTagAssign, MPI_COMM_WORLD),
              "MPI_Send");
        if (index < 0) --active;
    }
    local.join();
    return records;
}

}  // namespace tirpol::sweep::detail
