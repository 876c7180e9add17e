#pragma once

// The runs of a sweep (sweep_run.cpp): what every run needs (Context, with the run cache), and
// the rounds that score grid points on the training runs and the chosen point on the held-out
// runs, each a DistributeWork over the runs (one payload per run, sweep_payload.hpp). Internal
// to the sweep; not installed.

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "casmap/core/progress.hpp"
#include "casmap/mapper/filter_params.hpp"
#include "casmap/pipeline/bench_runner.hpp"
#include "casmap/pipeline/distributed.hpp"
#include "casmap/pipeline/sweep.hpp"

namespace casmap::pipeline::detail {

using Point = std::vector<double>;

/// The training runs of this process, kept across grid points and rounds (growth, descent
/// lines) when SweepOptions::cache_runs: the paper maps per run and `a`; for a named pipeline
/// that maps the scans again (pre-filter, Kalman mapper), the simulated scans and poses (no
/// truth labels) and that run's StageMaps. A run is worked on by one thread at a time; the
/// lock guards the containers only. Results never depend on it.
class RunCache {
public:
    std::shared_ptr<const MappedBenchRun> Find(const std::string& run, int a) {
        const std::lock_guard<std::mutex> lock(mutex_);
        const auto it = maps_.find({run, a});
        return it != maps_.end() ? it->second : nullptr;
    }
    void Store(const std::string& run, int a, std::shared_ptr<const MappedBenchRun> map) {
        const std::lock_guard<std::mutex> lock(mutex_);
        maps_[{run, a}] = std::move(map);
    }
    std::shared_ptr<const SimulatedRun> FindSim(const std::string& run) {
        const std::lock_guard<std::mutex> lock(mutex_);
        const auto it = sims_.find(run);
        return it != sims_.end() ? it->second : nullptr;
    }
    void StoreSim(const std::string& run, std::shared_ptr<const SimulatedRun> sim) {
        const std::lock_guard<std::mutex> lock(mutex_);
        sims_[run] = std::move(sim);
    }
    StageMaps& Stages(const std::string& run) {
        const std::lock_guard<std::mutex> lock(mutex_);
        std::unique_ptr<StageMaps>& s = stages_[run];
        if (!s) {
            s = std::make_unique<StageMaps>(4);
        }
        return *s;
    }

private:
    std::mutex mutex_;
    std::map<std::pair<std::string, int>, std::shared_ptr<const MappedBenchRun>> maps_;
    std::map<std::string, std::shared_ptr<const SimulatedRun>> sims_;
    std::map<std::string, std::unique_ptr<StageMaps>> stages_;
};

/// Everything every run needs: settings, courses (training and held-out), trajectories.
struct Context {
    explicit Context(const SweepOptions& o) : opt(o) {}
    const SweepOptions& opt;
    BenchSettings settings;
    std::vector<std::string> tests;
    std::vector<std::uint64_t> seeds;       // training
    std::vector<std::uint64_t> held_seeds;  // held-out
    std::vector<int> held_courses;
    std::vector<int> all_courses;                // sorted union
    std::vector<Course> loaded;                  // per all_courses
    std::optional<mapper::FilterMethod> method;  // nullopt: opt.filter via ScorePipelines
    bool maps_scans = false;  // opt.filter maps the scans again (a pre-filter, Kalman mapper)
    int threads = 1;
    const DistributedSession* session = nullptr;
    mutable RunCache cache;
    mutable std::atomic<std::size_t> simulated_runs{0};  // training rounds, this process
    mutable std::atomic<std::size_t> paper_maps{0};

    const Course& CourseOf(int number) const {
        const auto it = std::lower_bound(all_courses.begin(), all_courses.end(), number);
        return loaded[static_cast<std::size_t>(it - all_courses.begin())];
    }
};

/// One training run (seed, speed, course, test) and its name in the report.
struct TrainRun {
    std::uint64_t seed;
    double speed;
    int course;
    std::string test;
    std::string name;
};

/// The training runs in report order: seed, then speed, course, test.
[[nodiscard]] std::vector<TrainRun> TrainingRuns(const Context& cx, const SweepOptions& opt);

/// One training round: scores `points` on every run they apply to.
[[nodiscard]] std::map<Point, SweepPoint> TrainRound(const Context& cx,
                                                     const SweepOptions& opt,
                                                     const std::vector<Point>& points,
                                                     const core::ProgressFn& progress,
                                                     std::map<std::string, std::string>& configs);

/// Scores the chosen point and the paper's CAS on every held-out run.
[[nodiscard]] std::vector<HeldOutRun> HeldOut(const Context& cx,
                                              const SweepOptions& opt,
                                              const Point& best,
                                              const core::ProgressFn& progress);

}  // namespace casmap::pipeline::detail
