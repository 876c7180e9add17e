// casmap bench [--courses 1-16] [--tests T,TR,TP,TRP] [--seed N] [--out DIR] [--json FILE]
//              [--rig RIG.yaml] [--sensor LMS200.yaml]
// The paper's benchmark: for each obstacle course x test, simulate the table run, map it, run
// CAS and the four baselines and score them against the exact ground truth (Eq. 11 PI, RMSE,
// surviving spikes, filled-cell error, Table II classes). Runs in parallel across courses and
// tests, one thread per run, so the figures do not depend on --threads.
// Outputs (DIR, default out/bench): bench.json, pi_chart.png (Fig. 8), table2.md (Table II),
// poles.md, pi_table.txt, sheets/courseNN_TEST.png (Fig. 7), runs/courseNN_TEST.yaml (effective
// config).
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "apps/casmap/commands.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/core/parallel.hpp"
#include "casmap/core/progress.hpp"
#include "casmap/io/atomic_file.hpp"
#include "casmap/io/sensor_config.hpp"
#include "casmap/pipeline/bench_runner.hpp"

namespace casmap::app {
namespace {
namespace fs = std::filesystem;

struct BenchOptions {
    std::string courses = "1-16";
    std::string tests = "T,TR,TP,TRP";
    std::uint64_t seed = 1;
    std::string out = "out/bench";
    std::string json;
    std::string courses_dir;
    std::string rig;
    std::string sensor;  // --sensor: LMS 200 YAML
    std::vector<std::string> set;
    bool no_sheets = false;
};

std::string FilterParamsYaml(const mapper::FilterParams& p) {
    const mapper::CasParams& c = p.cas;
    return "filters:\n  cas: {k: " + std::to_string(c.k) + ", a: " + std::to_string(c.a) +
           ", cell_m: " + FormatNumber(c.cell_m) + ", speed_m_s: " + FormatNumber(c.speed_m_s) +
           ", scan_period_s: " + FormatNumber(c.scan_period_s) +
           ", A: " + FormatNumber(c.EffectiveA()) + ", G: " + FormatNumber(c.EffectiveG()) +
           ", gs_mode: " + (c.gs_mode == mapper::GsMode::kSum ? "sum" : "variance") +
           ", h_sum_min: " + FormatNumber(c.h_sum_min) + ", B: " + FormatNumber(c.B) +
           ", normalise: " + (c.normalise == mapper::Normalise::kWindow ? "window" : "global") +
           ", e_term: " + (c.e_term ? "on" : "off") + ", E: " + FormatNumber(c.E) +
           ", wm_empty: " + (c.wm_empty == mapper::WmEmpty::kInclude ? "include" : "skip") +
           "}\n  baseline: {window: " + std::to_string(p.baseline.window) + ", noise: " +
           (p.baseline.noise ? FormatNumber(*p.baseline.noise) : "mean_local_variance") +
           ", center_weight: " + std::to_string(p.baseline.center_weight) + "}\n";
}

void RunBench(const BenchOptions& opt, const CommonOptions& common) {
    const auto start = std::chrono::steady_clock::now();
    // Validate everything before any work: bad input exits 2 at once.
    const std::vector<int> courses = ParseCourses(opt.courses, "--courses");
    const std::vector<std::string> tests = ParseTests(opt.tests, "--tests");
    BenchSettings settings = CheckBenchSettings(opt.courses_dir, opt.rig, opt.sensor, opt.seed);
    if (!opt.json.empty()) {
        CheckWritableFile(opt.json, "--json");
    }
    const fs::path out(opt.out);
    io::EnsureDirectory(out);
    io::EnsureDirectory(out / "runs");
    if (!opt.no_sheets) {
        io::EnsureDirectory(out / "sheets");
    }
    const int threads = core::ResolveThreads(common.threads);

    // The table trajectories depend on the test only (the rig does not see the scene).
    std::vector<SimSetup> setups(tests.size());
    for (std::size_t t = 0; t < tests.size(); ++t) {
        setups[t] = BenchSetup(settings, courses.front(), tests[t]);
    }
    mapper::FilterParams check;
    for (const std::string& assignment : opt.set) {
        check.SetAssignment(assignment);
    }
    check.Validate();
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
    std::vector<BenchRun> runs(n);
    {
        core::Progress progress("bench", n);
        core::ParallelFor(n, threads, [&](std::size_t k) {
            const Course& course = loaded[k / tests.size()];
            const std::size_t t = k % tests.size();
            SimSetup setup = setups[t];
            setup.scene_path = course.path;
            const MappedBenchRun run = SimulateAndMap(setup, course, trajectories[t], 3);
            const mapper::FilterParams params = RunFilterParams(run, opt.set);
            SheetMaps sheet;
            runs[k] = ScoreRun(run, course, params, opt.no_sheets ? nullptr : &sheet);
            const std::string name = RunName(course.number, tests[t]);
            io::WriteTextAtomically(out / "runs" / (name + ".yaml"),
                                    run.config_yaml + FilterParamsYaml(params));
            if (!opt.no_sheets) {
                WriteSheet(out / "sheets" / (name + ".png"), sheet,
                           "obstacle course " + std::to_string(course.number) + ", test " +
                               tests[t] + ": raw, ground truth and the five filters");
            }
            progress.Advance();
        });
        progress.Finish();
    }
    WritePiChart(out / "pi_chart.png", runs);
    io::WriteTextAtomically(out / "table2.md", TableTwoMarkdown(runs));
    io::WriteTextAtomically(out / "poles.md", PolesMarkdown(runs));
    const std::string table = PiTable(runs);
    io::WriteTextAtomically(out / "pi_table.txt", table);
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const std::string json = BenchJson(runs, elapsed, threads);
    io::WriteTextAtomically(out / "bench.json", json);
    if (!opt.json.empty()) {
        io::WriteTextAtomically(opt.json, json);
    }
    std::fputs(table.c_str(), stdout);
    std::printf("%zu runs in %.1f s on %d threads -> %s\n", n, elapsed, threads,
                out.string().c_str());
}

}  // namespace

void AddBenchCommand(CLI::App& app, CommonOptions& common) {
    auto opt = std::make_shared<BenchOptions>();
    CLI::App* sub = app.add_subcommand(
        "bench", "The paper's benchmark: 16 courses x T/TR/TP/TRP, CAS vs four baselines");
    sub->add_option("--courses", opt->courses, "courses, e.g. 1-16, 4 or 1,4,7-9")
        ->capture_default_str();
    sub->add_option("--tests", opt->tests, "tests: T,TR,TP,TRP")->capture_default_str();
    sub->add_option("--seed", opt->seed, "simulator seed (every run)")->capture_default_str();
    sub->add_option("--out", opt->out, "output directory")->capture_default_str();
    sub->add_option("--json", opt->json, "also write bench.json here");
    sub->add_option("--courses-dir", opt->courses_dir,
                    "directory of course01.yaml .. course16.yaml (default: scenes/courses)");
    sub->add_option("--rig", opt->rig, "rig YAML (table settings; default: the paper course)");
    sub->add_option("--sensor", opt->sensor,
                    "LMS 200 YAML (config/lms200.yaml; default: the built-in config)");
    sub->add_option("--set", opt->set, "filter parameter NAME=VALUE (see casmap filter)");
    sub->add_flag("--no-sheets", opt->no_sheets, "skip the per-run Fig. 7 sheets");
    AddThreadsOption(sub, common);
    sub->callback([opt, &common] { RunBench(*opt, common); });
}

}  // namespace casmap::app
