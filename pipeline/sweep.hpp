#pragma once

// A grid search over CAS parameters (A, G, B, h_sum_min, a, E, k) and the table speed on chosen
// courses and tests: the mean and spread of CAS's PI (Eq. 11) per grid point. Every course x
// test x speed is simulated once; `a` re-maps the simulated scans, every other parameter only
// re-runs the filter. Never prints; progress through a callback.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "casmap/core/progress.hpp"
#include "casmap/pipeline/bench.hpp"

namespace casmap::pipeline {

/// Parameters a sweep axis may name: A, G, B, h_sum_min, a, E, k, speed.
[[nodiscard]] const std::vector<std::string>& SweepableParameters();

/// One swept parameter and its values.
struct SweepAxis {
    std::string name;
    std::vector<double> values;
};

/// "NAME=FROM:TO:STEP" -> FROM, FROM + STEP, ... <= TO; InputError naming `field`.
[[nodiscard]] SweepAxis ParseSweepAxis(const std::string& assignment, const std::string& field);

struct SweepOptions {
    std::vector<SweepAxis> axes;              // each parameter once; <= 10000 points
    std::vector<std::string> fixed;           // NAME=VALUE filter settings at every point
    std::vector<int> courses = AllCourses();  // each in 1..16
    std::vector<std::string> tests = {"T"};   // subset of T, TR, TP, TRP
    std::uint64_t seed = 1;                   // simulator seed of every run
    std::string courses_dir;                  // empty: CoursesDir()
    std::string rig_path;                     // rig YAML; empty: the paper course
    std::string sensor_path;                  // LMS 200 YAML; empty: built-in config
    int threads = 0;                          // 0 = all cores; results never depend on it

    /// Throws InputError naming the field (axes, fixed, courses, tests, courses_dir, ...),
    /// the value and the rule; checks every grid point's filter settings and every speed.
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
    SweepStats pi;               // CAS's PI over the runs of this point
    double mixed_pct = 0.0;      // mean Table II shares of CAS over those runs
    double missing_pct = 0.0;
    double untouched_pct = 0.0;
    double spikes_mean = 0.0;             // CAS's surviving spikes, mean over the runs
    std::size_t runs_all_poles_kept = 0;  // runs in which CAS kept every pole of the course
};

struct SweepResult {
    SweepOptions options;                  // as given (axes, fixed, courses, tests, seed)
    std::vector<SweepPoint> points;        // row-major over the axes, first axis slowest
    std::size_t best = 0;                  // lowest finite mean PI
    std::vector<std::string> run_names;    // "course04_T" (+ "_speed0.5" when speed is swept)
    std::vector<std::string> run_configs;  // effective configuration YAML per run
    double elapsed_s = 0.0;
    int threads = 1;
};

/// Validates `options`, then simulates every speed x course x test once and scores every grid
/// point on the runs it applies to. `progress` is told once per simulated run.
[[nodiscard]] SweepResult RunSweep(const SweepOptions& options,
                                   const core::ProgressFn& progress = {});

/// sweep.json: parameters, fixed, courses, tests, seed, points, best_point, elapsed_s, threads.
[[nodiscard]] std::string SweepJson(const SweepResult& result);

/// The terminal table: one line per point (values, PI mean/std/min/max, runs), best marked.
[[nodiscard]] std::string SweepTable(const SweepResult& result);

/// Writes DIR/sweep.json, runs/<run>.yaml and, for two axes, heatmap.png. Creates DIR.
/// Returns the sweep.json text.
std::string WriteSweepOutputs(const std::filesystem::path& dir, const SweepResult& result);

}  // namespace casmap::pipeline
