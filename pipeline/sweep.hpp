#pragma once

// A grid search over the parameters of CAS or one of its variants (cas_trail, cas_terrain) and
// the table speed: per grid point the mean and spread of the filter's PI (Eq. 11), its surviving
// spikes and the poles it keeps, on TRAINING runs (seeds x courses x tests); the best point is
// chosen on those runs alone and then scored, beside the paper's defaults, on HELD-OUT runs
// (other seeds and/or courses). The grid grows outward while the best point sits on an edge.
// Runs spread over MPI ranks like `casmap bench` (distributed.hpp). Never prints; progress
// through a callback.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "casmap/core/progress.hpp"
#include "casmap/pipeline/bench.hpp"

namespace casmap::pipeline {

class DistributedSession;

/// Parameters a sweep axis may name: A, G, B, h_sum_min, a, E, k, speed, the variants'
/// support_tol_m, support_min (cas_trail, cas_median), ground_k, ground_quantile (cas_terrain),
/// surface_tol_m, surface_min (cas_median), and the mapping stages' numeric parameters
/// (shadow.*, range_jump.*, sweep_jump.*, kalman.*: only when the swept pipeline runs that stage,
/// e.g. --filter shadow_cas; InputError naming "axes" else).
[[nodiscard]] const std::vector<std::string>& SweepableParameters();

/// Filters a sweep tunes: cas, cas_trail, cas_terrain.
[[nodiscard]] const std::vector<std::string>& SweepableFilters();

/// One swept parameter and its values.
struct SweepAxis {
    std::string name;
    std::vector<double> values;
};

/// "NAME=FROM:TO:STEP" -> FROM, FROM + STEP, ... <= TO; InputError naming `field`.
[[nodiscard]] SweepAxis ParseSweepAxis(const std::string& assignment, const std::string& field);

/// "1-2", "3,7", "1,4-6" -> sorted unique seeds; InputError naming `field`.
[[nodiscard]] std::vector<std::uint64_t> ParseSeeds(const std::string& text,
                                                    const std::string& field);

struct SweepOptions {
    std::vector<SweepAxis> axes;              // each parameter once; <= 10000 points
    std::vector<std::string> fixed;           // NAME=VALUE filter settings at every point
    std::string filter = "cas";               // cas, cas_trail or cas_terrain
    std::vector<int> courses = AllCourses();  // training courses, each in 1..16
    std::vector<std::string> tests = {"T"};   // subset of T, TR, TP, TRP (training and held-out)
    std::uint64_t seed = 1;                   // training seed when `seeds` is empty
    std::vector<std::uint64_t> seeds;         // training seeds (empty: {seed})
    std::vector<std::uint64_t> test_seeds;    // held-out seeds (empty: the training seeds)
    std::vector<int> test_courses;            // held-out courses (empty: the training courses)
    int grow = 0;                             // growth rounds (0..20): extend edge axes
    std::string search = "grid";              // grid (every point) or descent (coordinate)
    std::string courses_dir;                  // empty: CoursesDir()
    std::string rig_path;                     // rig YAML; empty: the paper course
    std::string sensor_path;                  // LMS 200 YAML; empty: built-in config
    int threads = 0;                          // 0 = all cores; results never depend on it
    const DistributedSession* session = nullptr;  // null: local threads only
    /// Keep each process's training runs across grid points and rounds (growth, descent
    /// lines): the simulated beams and poses (named pipelines that map again only), the paper
    /// maps per `a`, and up to 4 pre-filter / Kalman maps per run. false: simulate every run
    /// each round and map every point anew (the reference the cache is tested against).
    /// Results never depend on it.
    bool cache_runs = true;

    /// The training seeds: `seeds`, or {seed}.
    [[nodiscard]] std::vector<std::uint64_t> TrainSeeds() const;
    /// True when held-out runs are asked for (test_seeds or test_courses given).
    [[nodiscard]] bool HasHeldOut() const { return !test_seeds.empty() || !test_courses.empty(); }

    /// Throws InputError naming the field (axes, fixed, filter, courses, tests, seeds,
    /// test_seeds, test_courses, grow, courses_dir, ...), the value and the rule; checks every
    /// grid point's filter settings and every speed, and that no held-out run (seed, course) is
    /// also a training run.
    void Validate() const;
};

/// Mean, population spread, extremes of the finite values and how many there were.
struct SweepStats {
    double mean = std::numeric_limits<double>::quiet_NaN();
    double std = std::numeric_limits<double>::quiet_NaN();
    double min = std::numeric_limits<double>::quiet_NaN();
    double max = std::numeric_limits<double>::quiet_NaN();
    std::size_t runs = 0;
};
[[nodiscard]] SweepStats Summarise(const std::vector<double>& values);

struct SweepPoint {
    std::vector<double> values;  // one per axis
    SweepStats pi;               // the filter's PI over the runs of this point
    double mixed_pct = 0.0;      // mean Table II shares over those runs
    double missing_pct = 0.0;
    double untouched_pct = 0.0;
    double spikes_mean = 0.0;             // surviving spikes, mean over the runs
    std::int64_t spikes_total = 0;        // and their sum
    std::size_t runs_scored = 0;          // runs this point was scored on
    std::size_t runs_all_poles_kept = 0;  // runs in which every pole of the course was kept
    std::size_t poles = 0;                // poles over the runs (a pole counts once per run)
    std::size_t poles_kept = 0;           // of those, kept (ScoreRun's rule)

    [[nodiscard]] bool KeepsEveryPole() const {
        return runs_scored > 0 && runs_all_poles_kept == runs_scored;
    }
};

/// One growth round: the axis extended, its new values, the best point that caused it.
struct SweepGrowth {
    int round = 0;
    std::string axis;
    std::vector<double> added;
    std::vector<double> best_before;  // the best point's values before the round
};

/// One filter's score on one held-out run.
/// One step of a coordinate descent: after the line search along `axis` in `pass`, the best
/// point and how many points had been scored.
struct SweepStep {
    int pass = 0;
    std::string axis;
    std::vector<double> best;
    std::size_t scored = 0;
};

struct HeldOutScore {
    double pi = std::numeric_limits<double>::quiet_NaN();
    std::int64_t spikes = 0;
    std::size_t poles = 0;
    std::size_t poles_kept = 0;
};

struct HeldOutRun {
    std::string name;  // "seed3_course04_T"
    std::uint64_t seed = 0;
    int course = 0;
    std::string test;
    HeldOutScore chosen;  // the chosen point
    HeldOutScore paper;   // CAS at the paper's defaults (no overrides) on the same run
};

struct SweepResult {
    SweepOptions options;                  // as given, axes as grown
    std::vector<SweepPoint> points;        // scored points, row-major over the axes (first
                                           // axis slowest); descent scores a subset
    std::size_t best = 0;                  // the chosen point (rule in best_rule)
    bool best_keeps_every_pole = false;    // false: no point kept every pole (fallback rule)
    std::string best_rule;                 // the rule that chose `best`, in words
    std::vector<std::size_t> pareto;       // non-dominated points (PI, poles kept, spikes)
    std::vector<SweepGrowth> growth;       // growth rounds, in order
    std::vector<SweepStep> path;           // descent only: the best point after each line
    std::vector<std::string> run_names;    // training runs: "course04_T" (+ "_seedS", "_speedV")
    std::vector<std::string> run_configs;  // effective configuration YAML per training run
    std::vector<HeldOutRun> held_out;      // empty without held-out runs
    double elapsed_s = 0.0;
    int threads = 1;
    int ranks = 1;
    /// Work this process did for the training rounds (not in sweep.json: it depends on the
    /// run cache and the rank count, the figures do not): runs simulated, paper maps made.
    std::size_t simulated_runs = 0;
    std::size_t paper_maps = 0;
};

/// Validates `options`, then simulates every training run (seed x speed x course x test) and
/// scores every grid point on the runs it applies to; grows the grid while the best point sits
/// on an edge (options.grow rounds at most); then scores the chosen point and the paper's CAS on
/// the held-out runs. `progress` is told once per simulated run (rank 0). Under MPI every rank
/// must call it; rank 0 gets the full result, other ranks the same result (rank 0's, broadcast).
[[nodiscard]] SweepResult RunSweep(const SweepOptions& options,
                                   const core::ProgressFn& progress = {});

/// sweep.json: parameters, filter, fixed, train/test sets, points, best_point, best_rule,
/// pareto_front, growth, held_out, elapsed_s, threads.
[[nodiscard]] std::string SweepJson(const SweepResult& result);

/// The terminal table: one line per point (values, PI mean/std/min/max, spikes, poles kept),
/// best marked, then the growth path and the held-out comparison.
[[nodiscard]] std::string SweepTable(const SweepResult& result);

/// Writes DIR/sweep.json, runs/<run>.yaml and, for two axes, heatmap.png (points keeping every
/// pole framed, the chosen one starred). Creates DIR. Returns the sweep.json text.
std::string WriteSweepOutputs(const std::filesystem::path& dir, const SweepResult& result);

/// The sweep as `casmap sweep` runs it: validates `options` and checks `json_copy` (an extra
/// copy of sweep.json; empty: none; InputError with the path as `where`, field "json") before
/// any work, runs RunSweep in a DistributedSession of its own (MPI under mpirun/srun, else one
/// rank; options.session is replaced), and on rank 0 writes WriteSweepOutputs(out_dir) and the
/// copy. Returns the result on rank 0 (its options.session cleared), nullopt on other ranks.
[[nodiscard]] std::optional<SweepResult> RunSweepToFolder(SweepOptions options,
                                                          const std::filesystem::path& out_dir,
                                                          const std::string& json_copy,
                                                          const core::ProgressFn& progress = {});

}  // namespace casmap::pipeline
