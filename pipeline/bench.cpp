#include "casmap/pipeline/bench.hpp"

#include <chrono>
#include <numeric>
#include <set>
#include <stdexcept>

#include "casmap/core/input_error.hpp"
#include "casmap/core/parallel.hpp"
#include "casmap/io/atomic_file.hpp"
#include "casmap/pipeline/bench_maps.hpp"
#include "casmap/pipeline/bench_runner.hpp"
#include "casmap/pipeline/bench_wire.hpp"
#include "casmap/pipeline/distributed.hpp"

namespace casmap::pipeline {
namespace {
namespace fs = std::filesystem;

std::string OnOff(bool on) { return on ? "on" : "off"; }

}  // namespace

std::vector<int> AllCourses() {
    std::vector<int> all;
    for (int c = 1; c <= 16; ++c) {
        all.push_back(c);
    }
    return all;
}

const std::vector<std::string>& AllTests() {
    static const std::vector<std::string> tests = {"T", "TR", "TP", "TRP"};
    return tests;
}

void BenchOptions::Validate() const {
    CheckCoursesAndTests(courses, tests);
    (void)ResolveBenchSettings(courses_dir, rig_path, sensor_path, seed);
    mapper::FilterParams check;
    for (const std::string& assignment : filter_settings) {
        check.SetAssignment(assignment);
    }
    check.Validate();
}

std::string FilterParamsYaml(const mapper::FilterParams& p) {
    const mapper::CasParams& c = p.cas;
    return "filters:\n  cas: {k: " + std::to_string(c.k) + ", a: " + std::to_string(c.a) +
           ", cell_m: " + FormatNumber(c.cell_m) + ", speed_m_s: " + FormatNumber(c.speed_m_s) +
           ", scan_period_s: " + FormatNumber(c.scan_period_s) +
           ", A: " + FormatNumber(c.EffectiveA()) + ", G: " + FormatNumber(c.EffectiveG()) +
           ", gs_mode: " + (c.gs_mode == mapper::GsMode::kSum ? "sum" : "variance") +
           ", h_sum_min: " + FormatNumber(c.h_sum_min) + ", B: " + FormatNumber(c.B) +
           ", normalise: " + (c.normalise == mapper::Normalise::kWindow ? "window" : "global") +
           ", e_term: " + OnOff(c.e_term) + ", E: " + FormatNumber(c.E) +
           ", wm_empty: " + (c.wm_empty == mapper::WmEmpty::kInclude ? "include" : "skip") +
           "}\n  baseline: {window: " + std::to_string(p.baseline.window) + ", noise: " +
           (p.baseline.noise ? FormatNumber(*p.baseline.noise) : "mean_local_variance") +
           ", center_weight: " + std::to_string(p.baseline.center_weight) + "}\n";
}

BenchResult RunBench(const BenchOptions& options, const core::ProgressFn& progress) {
    const auto start = std::chrono::steady_clock::now();
    options.Validate();  // bad input fails before any work
    const BenchSettings settings = ResolveBenchSettings(options.courses_dir, options.rig_path,
                                                        options.sensor_path, options.seed);
    const std::vector<int>& courses = options.courses;
    const std::vector<std::string> tests = SortedTests(options.tests);
    const int threads = core::ResolveThreads(options.threads);

    // The table trajectories depend on the test only (the rig does not see the scene).
    std::vector<SimSetup> setups(tests.size());
    for (std::size_t t = 0; t < tests.size(); ++t) {
        setups[t] = BenchSetup(settings, courses.front(), tests[t]);
    }
    std::vector<core::Trajectory> trajectories(tests.size());
    std::vector<Course> loaded;
    core::ParallelFor(tests.size() + 1, threads, [&](std::size_t i) {
        if (i < tests.size()) {
            trajectories[i] = RigTrajectory(setups[i], core::Scene{});
        } else {
            loaded = LoadCourses(settings, courses, setups.front().grid, 1);
        }
    });

    const std::size_t n = courses.size() * tests.size();
    BenchResult result;
    result.runs.resize(n);
    result.run_names.resize(n);
    result.run_configs.resize(n);
    result.grids.resize(n);
    result.write_sheets = options.sheets;
    result.write_maps = options.maps;
    const bool keep_maps = options.sheets || options.maps;
    if (keep_maps) {
        result.sheets.resize(n);
    }
    core::ProgressCounter counter(progress, n);
    std::vector<std::size_t> items(n);
    std::iota(items.begin(), items.end(), std::size_t{0});
    const DistributedSession local = DistributedSession::Local();
    const DistributedSession& session = options.session != nullptr ? *options.session : local;
    // A run travels as 'R' + EncodeBenchRun, or 'E' + the error that stopped it.
    const auto work = [&](std::size_t k) -> std::string {
        try {
            const Course& course = loaded[k / tests.size()];
            const std::size_t t = k % tests.size();
            SimSetup setup = setups[t];
            setup.scene_path = course.path;
            const MappedBenchRun run = SimulateAndMap(setup, course, trajectories[t], 3);
            const mapper::FilterParams params = RunFilterParams(run, options.filter_settings);
            BenchRunRecord record;
            record.has_sheet = keep_maps;
            record.run = ScoreRun(run, course, params, keep_maps ? &record.sheet : nullptr);
            record.name = RunName(course.number, tests[t]);
            record.config_yaml = run.config_yaml + FilterParamsYaml(params);
            return "R" + EncodeBenchRun(record);
        } catch (const std::exception& e) {
            return std::string("E") + e.what();
        }
    };
    std::string error;
    const auto done = [&](std::size_t k, const std::string& payload) {
        if (payload.front() == 'E') {
            error = error.empty() ? payload.substr(1) : error;
            return;
        }
        BenchRunRecord record = DecodeBenchRun(payload.substr(1));
        result.runs[k] = std::move(record.run);
        result.run_names[k] = std::move(record.name);
        result.run_configs[k] = std::move(record.config_yaml);
        if (keep_maps) {
            result.sheets[k] = std::move(record.sheet);
        }
        result.grids[k] = setups[k % tests.size()].grid;
        counter.Advance();
    };
    (void)DistributeWork(session, items, threads, work, done);
    if (!error.empty()) {
        throw std::runtime_error(error);
    }
    result.threads = threads;
    result.elapsed_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
}

std::string WriteBenchOutputs(const fs::path& dir, const BenchResult& result) {
    const auto start = std::chrono::steady_clock::now();
    io::EnsureDirectory(dir);
    io::EnsureDirectory(dir / "runs");
    const bool sheets = !result.sheets.empty() && result.write_sheets;
    const bool maps = !result.sheets.empty() && result.write_maps;
    if (sheets) {
        io::EnsureDirectory(dir / "sheets");
    }
    core::ParallelFor(result.runs.size(), result.threads, [&](std::size_t k) {
        const std::string& name = result.run_names[k];
        io::WriteTextAtomically(dir / "runs" / (name + ".yaml"), result.run_configs[k]);
        if (sheets) {
            const BenchRun& r = result.runs[k];
            WriteSheet(dir / "sheets" / (name + ".png"), result.sheets[k],
                       "obstacle course " + std::to_string(r.course) + ", test " + r.test +
                           ": raw, ground truth and the five filters");
        }
        if (maps) {
            WriteBenchMaps(dir / "runs" / name, result.sheets[k], result.grids[k]);
        }
    });
    WritePiChart(dir / "pi_chart.png", result.runs);
    io::WriteTextAtomically(dir / "table2.md", TableTwoMarkdown(result.runs));
    io::WriteTextAtomically(dir / "poles.md", PolesMarkdown(result.runs));
    io::WriteTextAtomically(dir / "pi_table.txt", PiTable(result.runs));
    const double elapsed =
        result.elapsed_s +
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::string json = BenchJson(result.runs, elapsed, result.threads);
    io::WriteTextAtomically(dir / "bench.json", json);
    return json;
}

}  // namespace casmap::pipeline
