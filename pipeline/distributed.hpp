#pragma once

// Work spread over MPI ranks (built when CASMAP_WITH_MPI and MPI are found), the engine behind
// `mpirun casmap dataset` and usable by any loop of independent items (bench runs, sweep
// points): dynamic scheduling, rank 0 hands out item numbers as ranks ask for work (items may
// differ a lot in cost), each rank computes its items and sends back a text payload, rank 0
// collects them. Without MPI, or when the process was not started by an MPI launcher, the same
// calls run on local threads. Results never depend on the rank or thread count as long as
// work(i) depends only on i.

#include <cstddef>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace casmap::pipeline {

/// True when this build has MPI support.
[[nodiscard]] bool MpiBuilt();

/// True when this build has MPI and the process was started by an MPI launcher (mpirun,
/// mpiexec, srun: OMPI_COMM_WORLD_SIZE, PMI_SIZE or PMIX_RANK in the environment).
[[nodiscard]] bool LaunchedByMpi();

/// MPI for a scope: initialises MPI (MPI_THREAD_FUNNELED) when LaunchedByMpi() and nobody did
/// yet, finalises it at the end if it initialised it. Otherwise rank 0 of 1. One per process.
class DistributedSession {
public:
    DistributedSession();
    /// Rank 0 of 1 whatever the launcher: threads only.
    [[nodiscard]] static DistributedSession Local();
    ~DistributedSession();
    DistributedSession(const DistributedSession&) = delete;
    DistributedSession& operator=(const DistributedSession&) = delete;

    [[nodiscard]] int rank() const { return rank_; }
    [[nodiscard]] int ranks() const { return ranks_; }
    /// Blocks until every rank arrives (no-op with one rank).
    void Barrier() const;
    /// Rank 0's `text` on every rank (collective: every rank calls it; one rank: `text`).
    [[nodiscard]] std::string Broadcast(std::string text) const;

private:
    struct LocalTag {};
    explicit DistributedSession(LocalTag /*unused*/) {}
    int rank_ = 0;
    int ranks_ = 1;
    bool owner_ = false;
};

using WorkFn = std::function<std::string(std::size_t item)>;
using DoneFn = std::function<void(std::size_t item, const std::string& payload)>;

/// Runs work(i) for every i in `items` over every rank of `session`: rank 0 runs `threads`
/// local workers (at least 1) beside the scheduler on its main thread; other ranks compute one
/// item at a time. On rank 0 returns every payload keyed by item and calls `done` (may be
/// empty) as items finish, serialised; other ranks return an empty map. `work` must not throw
/// (turn failures into payloads). With one rank: `threads` local workers only.
[[nodiscard]] std::map<std::size_t, std::string> DistributeWork(
    const DistributedSession& session,
    const std::vector<std::size_t>& items,
    int threads,
    const WorkFn& work,
    const DoneFn& done);

}  // namespace casmap::pipeline
