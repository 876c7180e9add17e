#pragma once

// The paper's benchmark as building blocks for `casmap bench` and `casmap sweep`: the obstacle
// courses (scene, Embree world, ground truth), the table trajectories per test, one simulated
// and mapped run per course x test, and the scoring of the five filters against the truth.

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "casmap/mapper/filter_params.hpp"
#include "casmap/pipeline/benchmark_report.hpp"
#include "casmap/pipeline/map_run.hpp"
#include "casmap/pipeline/sim_pipeline.hpp"

namespace casmap::pipeline {

/// "1-16", "4", "1,3,7-9" -> sorted unique courses in 1..16; InputError naming `field`.
[[nodiscard]] std::vector<int> ParseCourses(const std::string& text, const std::string& field);
/// "T,TR,TP,TRP" subset, in that order; InputError naming `field`.
[[nodiscard]] std::vector<std::string> ParseTests(const std::string& text,
                                                  const std::string& field);
/// Throws InputError naming "courses" or "tests" unless every course is in 1..16 and every
/// test one of T, TR, TP, TRP, none repeated and neither list empty.
void CheckCoursesAndTests(const std::vector<int>& courses, const std::vector<std::string>& tests);
/// `tests` in the order T, TR, TP, TRP.
[[nodiscard]] std::vector<std::string> SortedTests(const std::vector<std::string>& tests);
/// The courses directory: `dir` if given (InputError naming "courses_dir" unless it holds
/// course01.yaml), else CoursesDir() (data_dir.hpp).
[[nodiscard]] std::string FindCoursesDir(const std::string& dir);
/// <dir>/courseNN.yaml.
[[nodiscard]] std::string CoursePath(const std::string& dir, int course);
/// "course04_T".
[[nodiscard]] std::string RunName(int course, const std::string& test);

/// One obstacle course, loaded once and shared (read-only) by all its runs.
struct Course {
    int number = 0;
    std::string path;
    core::Scene scene;
    std::unique_ptr<sim::World> world;
    core::MapF truth;  // on the benchmark grid
};

/// Settings common to every run of a bench or sweep.
struct BenchSettings {
    std::string courses_dir;
    std::string rig_path;     // optional rig YAML
    std::string sensor_path;  // optional LMS 200 YAML (io/sensor_config.hpp)
    std::uint64_t seed = 1;
    std::optional<double> speed_m_s;
};

/// Resolves and checks the settings before any work: the courses directory exists and a
/// sensor file (if any) loads. Throws InputError naming the field or file.
[[nodiscard]] BenchSettings ResolveBenchSettings(const std::string& courses_dir,
                                                 const std::string& rig_path,
                                                 const std::string& sensor_path,
                                                 std::uint64_t seed);

/// The setup of one run (rig, sensor, grid) for a course and test.
[[nodiscard]] SimSetup BenchSetup(const BenchSettings& settings,
                                  int course,
                                  const std::string& test);

/// Loads the courses in parallel (scene, world, ground truth on `grid`).
[[nodiscard]] std::vector<Course> LoadCourses(const BenchSettings& settings,
                                              const std::vector<int>& courses,
                                              const core::GridGeometry& grid,
                                              int threads);

/// One simulated and mapped run.
struct MappedBenchRun {
    int course = 0;
    std::string test;
    SimSetup setup;
    std::size_t scans = 0;
    MappedRun mapped;
    std::string config_yaml;  // the run's effective configuration
};

/// Simulates one run (one thread, no truth: the course holds it).
[[nodiscard]] SimulatedRun SimulateBenchRun(const SimSetup& setup,
                                            const Course& course,
                                            const core::Trajectory& poses);

/// Maps a simulated run on the setup's grid with the paper's mapper (Eq. 1-6), its `a` and
/// the unknown-cell convention.
[[nodiscard]] MappedBenchRun MapBenchRun(const SimSetup& setup,
                                         const Course& course,
                                         const SimulatedRun& sim,
                                         int a,
                                         mapper::Unknown unknown = mapper::Unknown::kZero);

/// SimulateBenchRun then MapBenchRun.
[[nodiscard]] MappedBenchRun SimulateAndMap(const SimSetup& setup,
                                            const Course& course,
                                            const core::Trajectory& poses,
                                            int a);

/// The filter parameters a setup implies (cell size, the table's or vehicle's speed, scan
/// period, `a`, `unknown`), then `overrides` (NAME=VALUE, FilterParams::Set: a preset's
/// settings, then --set) applied, then validated.
[[nodiscard]] mapper::FilterParams SetupFilterParams(const SimSetup& setup,
                                                     int a,
                                                     mapper::Unknown unknown,
                                                     const std::vector<std::string>& overrides);

/// SetupFilterParams for a mapped run (its setup, a and unknown convention).
[[nodiscard]] mapper::FilterParams RunFilterParams(const MappedBenchRun& run,
                                                   const std::vector<std::string>& overrides);

/// Any scene file as a benchmark "course" (number 0): scene, world, truth on `grid` (the
/// datum clamp of sim::GroundTruthElevation's default: terrain scenes keep negative heights).
[[nodiscard]] Course LoadSceneCourse(const std::string& path, const core::GridGeometry& grid);

/// Maps of one run's scans under other mapper modes / scan pre-filters (ScorePipelines makes
/// them), keyed by everything such a map depends on besides the scans and grid: mapper mode,
/// pre-filter, a, delta-l, unknown convention and the stage's parameters (shadow.*,
/// range_jump.*, sweep_jump.*, kalman.*). A caller scoring one run many times (a sweep over filter
/// parameters) keeps one per run so each stage setting is mapped once. Holds at most
/// `capacity` maps, the oldest made leaving first; one map is about 8 bytes per grid cell
/// (200 x 80 cells: 128 KB). Not thread-safe: one run, one user at a time.
class StageMaps {
public:
    explicit StageMaps(std::size_t capacity = 4) : capacity_(capacity < 1 ? 1 : capacity) {}
    [[nodiscard]] std::shared_ptr<const MappedRun> Find(const std::string& key) const;
    void Add(const std::string& key, std::shared_ptr<const MappedRun> map);
    [[nodiscard]] std::size_t size() const { return maps_.size(); }
    [[nodiscard]] std::size_t made() const { return made_; }  // maps added in all

private:
    std::size_t capacity_;
    std::size_t made_ = 0;
    std::vector<std::pair<std::string, std::shared_ptr<const MappedRun>>> maps_;  // oldest first
};

/// Runs the named pipelines (bench_pipelines.hpp) on one run and scores each against the
/// course's truth over the paper's region, Eq. 11's denominator being `run`'s map (the plain
/// raw map). Pipelines with another mapper mode or a scan pre-filter map `sim`'s scans again
/// (same beams, no new simulation); `sim` may be null when none does (InputError otherwise).
/// The map filters use `params` (unknown convention included), or `own.at(name)` for a
/// pipeline listed there (a preset's `pipelines:` section); Table II classes and the
/// fill-error cells always come from the paper CAS with `params`. Fills `sheet` (raw, truth,
/// every pipeline's map, CAS classes) when non-null. `stage_maps` (may be null: maps made for
/// this call only) supplies and keeps the re-made maps across calls on the same `sim`; the
/// figures never depend on it.
[[nodiscard]] BenchRun ScorePipelines(const MappedBenchRun& run,
                                      const SimulatedRun* sim,
                                      const Course& course,
                                      const mapper::FilterParams& params,
                                      const std::vector<std::string>& pipelines,
                                      SheetMaps* sheet,
                                      const std::map<std::string, mapper::FilterParams>& own = {},
                                      StageMaps* stage_maps = nullptr);

/// ScorePipelines with the paper's five filters (no re-mapping).
[[nodiscard]] BenchRun ScoreRun(const MappedBenchRun& run,
                                const Course& course,
                                const mapper::FilterParams& params,
                                SheetMaps* sheet);

/// One CAS-kind filter alone (for sweeps; `method` cas, cas_trail or cas_terrain): PI, Table II
/// shares, spikes and poles kept.
struct CasScore {
    double pi = 0.0;
    mapper::ClassReport classes;
    std::int64_t spikes = 0;     // surviving spikes over the paper's region (CountSpikes)
    std::size_t poles = 0;       // poles of the course inside the grid
    std::size_t poles_kept = 0;  // of those, kept by CAS (ScoreRun's rule)
};
[[nodiscard]] CasScore ScoreCas(const MappedBenchRun& run,
                                const Course& course,
                                const mapper::FilterParams& params,
                                mapper::FilterMethod method = mapper::FilterMethod::kCas);

}  // namespace casmap::pipeline
