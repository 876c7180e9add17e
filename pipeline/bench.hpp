#pragma once

// The paper's benchmark as one library call: for each obstacle course x test, simulate the
// table run, map it, run CAS and the four baselines and score them against the exact ground
// truth (Eq. 11 PI, RMSE, surviving spikes, filled-cell error, Table II classes, poles kept).
// Runs in parallel across courses and tests, one thread per run, so the figures do not depend
// on the thread count. Never prints; progress through a callback.

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "casmap/core/progress.hpp"
#include "casmap/mapper/filter_params.hpp"
#include "casmap/pipeline/bench_pipelines.hpp"
#include "casmap/pipeline/benchmark_report.hpp"

namespace casmap::pipeline {

class DistributedSession;  // distributed.hpp

/// Courses 1..16 (the paper's Table I).
[[nodiscard]] std::vector<int> AllCourses();
/// T, TR, TP, TRP (the paper's benchmark tests).
[[nodiscard]] const std::vector<std::string>& AllTests();

struct BenchOptions {
    std::vector<int> courses = AllCourses();      // each in 1..16, no repeats; may be empty
                                                  // when `scenes` is not
    std::vector<std::string> tests = AllTests();  // subset of T, TR, TP, TRP, no repeats
    /// Named pipelines scored per run (bench_pipelines.hpp); default: the paper's five.
    std::vector<std::string> pipelines = PaperPipelineNames();
    /// Further scene files (any scene YAML: outdoor, generated terrain), each run with every
    /// motion of `scene_motions` (T, TR, TP, TRP, vehicle) after the courses. Unknown cells
    /// are NaN on these runs (0 on the courses) unless --set unknown= says otherwise.
    std::vector<std::string> scenes;
    std::vector<std::string> scene_motions = {"vehicle"};
    /// Filter-parameter preset (preset.hpp) applied before filter_settings; empty = the
    /// built-in defaults (= the `paper` preset).
    std::string preset;
    std::uint64_t seed = 1;                    // simulator seed of every run
    std::string courses_dir;                   // course01.yaml ..; empty: CoursesDir()
    std::string rig_path;                      // rig YAML; empty: the paper course
    std::string sensor_path;                   // LMS 200 YAML; empty: built-in config
    std::vector<std::string> filter_settings;  // NAME=VALUE (mapper::FilterParams::Set)
    bool sheets = true;                        // keep the maps for the Fig. 7 sheets
    bool maps = false;  // also keep them for runs/<run>/*.tif + maps.json (bench_maps.hpp)
    int threads = 0;    // 0 = all cores; results never depend on it
    /// MPI ranks to spread the runs over (distributed.hpp; rank 0 gets the result, other
    /// ranks an empty one); null: local threads only. Results never depend on it.
    const DistributedSession* session = nullptr;

    /// Throws InputError naming the field (courses, tests, pipelines, scenes, scene_motions,
    /// preset, courses_dir, rig_path, sensor_path, filter_settings), the value and the rule.
    void Validate() const;
    /// The preset's settings (if any) followed by filter_settings: what every run applies.
    [[nodiscard]] std::vector<std::string> EffectiveFilterSettings() const;
    /// Per pipeline with a `pipelines:` section in the preset: the preset's settings, that
    /// section's, then filter_settings (--set overrides the preset). Empty without a preset.
    [[nodiscard]] std::map<std::string, std::vector<std::string>> PipelineFilterSettings() const;
};

struct BenchResult {
    std::vector<BenchRun> runs;             // course-major, tests in T, TR, TP, TRP order, then
                                            // the scene runs (scene-major, motions as given)
    std::vector<std::string> run_names;     // "course04_T" per run
    std::vector<std::string> run_configs;   // effective configuration YAML per run
    std::vector<SheetMaps> sheets;          // per run when BenchOptions::sheets or maps, else empty
    std::vector<core::GridGeometry> grids;  // the map grid per run
    bool write_sheets = true;               // WriteBenchOutputs draws sheets/<run>.png
    bool write_maps = false;                // WriteBenchOutputs writes runs/<run>/ maps
    std::vector<std::string> pipelines;     // the pipelines scored
    double elapsed_s = 0.0;                 // wall time of RunBench
    int threads = 1;                        // threads used
    int ranks = 1;                          // MPI ranks (RunBenchToFolder; RunBench: 1)
};

/// Validates `options`, then simulates, maps and scores every course x test. `progress` is
/// told once per finished run (total = courses x tests).
[[nodiscard]] BenchResult RunBench(const BenchOptions& options,
                                   const core::ProgressFn& progress = {});

/// Writes DIR/bench.json, pi_chart.png (Fig. 8), table2.md (Table II), poles.md,
/// pi_table.txt, pipelines.md (PipelinesMarkdown), runs/<run>.yaml and, when the result has them,
/// sheets/<run>.png (Fig. 7) and runs/<run>/*.tif + maps.json (WriteBenchMaps). Creates DIR.
/// bench.json's elapsed_s counts RunBench and the writing before it. Returns the bench.json text
/// written.
std::string WriteBenchOutputs(const std::filesystem::path& dir, const BenchResult& result);

/// The benchmark as `casmap bench` runs it: validates `options`, checks `out_dir`
/// (CheckBenchOutputFolder) and `json_copy` (an extra bench.json; empty: none) before any work,
/// runs RunBench in a DistributedSession of its own (MPI under mpirun/srun, else one rank;
/// options.session is replaced; `progress` on rank 0), and on rank 0 fills a temporary folder
/// with WriteBenchOutputs and swaps it in for `out_dir` together with the copy (io::OutputSet:
/// a failed or killed bench leaves the old folder). Output errors name `out` / `json` with the
/// path as `where`. Returns the result on rank 0, nullopt on other ranks.
[[nodiscard]] std::optional<BenchResult> RunBenchToFolder(BenchOptions options,
                                                          const std::filesystem::path& out_dir,
                                                          const std::string& json_copy,
                                                          const core::ProgressFn& progress = {});

/// A bench output folder replaces `dir` only if `dir` is missing, empty or a bench output (holds
/// bench.json): InputError "<dir>: out (holds files but no bench.json: ...)" otherwise.
void CheckBenchOutputFolder(const std::filesystem::path& dir);

/// The `filters:` section of a run's effective configuration (every CAS and baseline value).
[[nodiscard]] std::string FilterParamsYaml(const mapper::FilterParams& params);

}  // namespace casmap::pipeline
