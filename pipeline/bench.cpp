#include "casmap/pipeline/bench.hpp"

#include <algorithm>
#include <chrono>
#include <numeric>
#include <set>
#include <stdexcept>

#include "casmap/core/check.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/core/parallel.hpp"
#include "casmap/io/atomic_file.hpp"
#include "casmap/io/output_set.hpp"
#include "casmap/io/yaml_emit.hpp"
#include "casmap/mapper/stage_params.hpp"
#include "casmap/pipeline/bench_maps.hpp"
#include "casmap/pipeline/bench_runner.hpp"
#include "casmap/pipeline/bench_wire.hpp"
#include "casmap/pipeline/distributed.hpp"
#include "casmap/pipeline/preset.hpp"
#include "casmap/pipeline/stage_yaml.hpp"

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
    const core::Check check;
    if (!(courses.empty() && !scenes.empty())) {
        CheckCoursesAndTests(courses, tests);
    }
    CheckPipelines(pipelines);
    std::set<std::string> names;
    for (const std::string& scene : scenes) {
        if (!fs::is_regular_file(scene)) {
            check.Fail("scenes", scene, "no such scene file");
        }
        if (!names.insert(SceneRunStem(scene)).second) {
            check.Fail("scenes", scene,
                       "two scenes share the run name " + SceneRunStem(scene) +
                           " (runs are named after the file stem)");
        }
    }
    if (!scenes.empty()) {
        std::set<std::string> seen;
        for (const std::string& m : scene_motions) {
            const std::vector<std::string> all = {"T", "TR", "TP", "TRP", "vehicle"};
            if (std::find(all.begin(), all.end(), m) == all.end() || !seen.insert(m).second) {
                check.Fail("scene_motions", m,
                           "allowed: T, TR, TP, TRP, vehicle, each at most once");
            }
        }
        if (scene_motions.empty()) {
            check.Fail("scene_motions", "", "at least one motion");
        }
    }
    (void)ResolveBenchSettings(courses_dir, rig_path, sensor_path, seed);
    mapper::FilterParams params;
    for (const std::string& assignment : EffectiveFilterSettings()) {
        params.SetAssignment(assignment);
    }
    params.Validate();
    for (const auto& [pipeline, settings] : PipelineFilterSettings()) {
        mapper::FilterParams one;
        for (const std::string& assignment : settings) {
            one.SetAssignment(assignment);
        }
        one.Validate();
    }
}

std::map<std::string, std::vector<std::string>> BenchOptions::PipelineFilterSettings() const {
    std::map<std::string, std::vector<std::string>> out;
    if (preset.empty()) {
        return out;
    }
    const Preset loaded = LoadPreset(preset, "preset");
    for (const auto& [pipeline, settings] : loaded.pipeline_settings) {
        std::vector<std::string>& all = out[pipeline];
        all = loaded.settings;
        all.insert(all.end(), settings.begin(), settings.end());
        all.insert(all.end(), filter_settings.begin(), filter_settings.end());
    }
    return out;
}

std::vector<std::string> BenchOptions::EffectiveFilterSettings() const {
    std::vector<std::string> all;
    if (!preset.empty()) {
        all = LoadPreset(preset, "preset").settings;
    }
    all.insert(all.end(), filter_settings.begin(), filter_settings.end());
    return all;
}

std::string FilterParamsYaml(const mapper::FilterParams& p) {
    const mapper::CasParams& c = p.cas;
    YAML::Emitter out;
    out << YAML::BeginMap << YAML::Key << "filters" << YAML::Value << YAML::BeginMap;
    out << YAML::Key << "cas" << YAML::Value << YAML::Flow << YAML::BeginMap;
    out << YAML::Key << "k" << YAML::Value << c.k << YAML::Key << "a" << YAML::Value << c.a;
    io::EmitNumber(out, "cell_m", c.cell_m);
    io::EmitNumber(out, "speed_m_s", c.speed_m_s);
    io::EmitNumber(out, "scan_period_s", c.scan_period_s);
    io::EmitNumber(out, "A", c.EffectiveA());
    io::EmitNumber(out, "G", c.EffectiveG());
    out << YAML::Key << "gs_mode" << YAML::Value
        << (c.gs_mode == mapper::GsMode::kSum ? "sum" : "variance");
    io::EmitNumber(out, "h_sum_min", c.h_sum_min);
    io::EmitNumber(out, "B", c.B);
    out << YAML::Key << "normalise" << YAML::Value
        << (c.normalise == mapper::Normalise::kWindow ? "window" : "global");
    out << YAML::Key << "e_term" << YAML::Value << OnOff(c.e_term);
    io::EmitNumber(out, "E", c.E);
    out << YAML::Key << "wm_empty" << YAML::Value
        << (c.wm_empty == mapper::WmEmpty::kInclude ? "include" : "skip");
    if (c.unknown == mapper::Unknown::kNaN) {
        out << YAML::Key << "unknown" << YAML::Value << "nan";
    }
    out << YAML::EndMap;
    out << YAML::Key << "baseline" << YAML::Value << YAML::Flow << YAML::BeginMap;
    out << YAML::Key << "window" << YAML::Value << p.baseline.window;
    out << YAML::Key << "noise" << YAML::Value
        << (p.baseline.noise ? FormatNumber(*p.baseline.noise) : "mean_local_variance");
    out << YAML::Key << "center_weight" << YAML::Value << p.baseline.center_weight;
    out << YAML::EndMap;
    // The mapping stages' parameters (used only by the pipelines that run the stage).
    for (const mapper::StageSection& section : mapper::StageSections(p)) {
        detail::EmitStageSection(out, section);
    }
    out << YAML::EndMap << YAML::EndMap;
    return io::EmittedText(out);
}

BenchResult RunBench(const BenchOptions& options, const core::ProgressFn& progress) {
    const auto start = std::chrono::steady_clock::now();
    options.Validate();  // bad input fails before any work
    const BenchSettings settings = ResolveBenchSettings(options.courses_dir, options.rig_path,
                                                        options.sensor_path, options.seed);
    const std::vector<int>& courses = options.courses;
    const std::vector<std::string> tests =
        courses.empty() ? std::vector<std::string>{} : SortedTests(options.tests);
    const std::vector<std::string> filter_settings = options.EffectiveFilterSettings();
    const std::map<std::string, std::vector<std::string>> pipeline_settings =
        options.PipelineFilterSettings();
    const int threads = core::ResolveThreads(options.threads);

    // The table trajectories depend on the test only (the rig does not see the scene).
    std::vector<SimSetup> setups(tests.size());
    for (std::size_t t = 0; t < tests.size(); ++t) {
        setups[t] = BenchSetup(settings, courses.front(), tests[t]);
    }
    // Scene runs: scene-major, one setup per scene x motion (the vehicle follows the scene).
    const std::size_t n_courses = courses.size() * tests.size();
    const std::size_t n_motions = options.scene_motions.size();
    std::vector<SimSetup> scene_setups(options.scenes.size() * n_motions);
    for (std::size_t k = 0; k < scene_setups.size(); ++k) {
        SimFlags flags;
        flags.scene_path = options.scenes[k / n_motions];
        flags.motion = options.scene_motions[k % n_motions];
        flags.seed = settings.seed;
        flags.rig_path = settings.rig_path;
        flags.sensor_path = settings.sensor_path;
        scene_setups[k] = ResolveSimSetup(flags);
    }
    std::vector<core::Trajectory> trajectories(tests.size());
    std::vector<Course> loaded;
    std::vector<Course> scenes(options.scenes.size());
    core::ParallelFor(tests.size() + 1 + scenes.size(), threads, [&](std::size_t i) {
        if (i < tests.size()) {
            trajectories[i] = RigTrajectory(setups[i], core::Scene{});
        } else if (i == tests.size()) {
            if (!courses.empty()) {
                loaded = LoadCourses(settings, courses, setups.front().grid, 1);
            }
        } else {
            const std::size_t sc = i - tests.size() - 1;
            scenes[sc] = LoadSceneCourse(options.scenes[sc], scene_setups[sc * n_motions].grid);
        }
    });

    const std::size_t n = n_courses + scene_setups.size();
    BenchResult result;
    result.runs.resize(n);
    result.run_names.resize(n);
    result.run_configs.resize(n);
    result.grids.resize(n);
    result.write_sheets = options.sheets;
    result.write_maps = options.maps;
    result.pipelines = options.pipelines;
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
            const bool scene_run = k >= n_courses;
            const Course& course =
                scene_run ? scenes[(k - n_courses) / n_motions] : loaded[k / tests.size()];
            SimSetup setup = scene_run ? scene_setups[k - n_courses] : setups[k % tests.size()];
            setup.scene_path = course.path;
            const core::Trajectory poses =
                scene_run ? RigTrajectory(setup, course.scene) : core::Trajectory{};
            const SimulatedRun sim =
                SimulateBenchRun(setup, course, scene_run ? poses : trajectories[k % tests.size()]);
            // Unknown cells: 0 on the paper's courses, NaN on other scenes; --set unknown=
            // (or a preset) decides for the mapper and the filters alike.
            const mapper::FilterParams params = SetupFilterParams(
                setup, 3, scene_run ? mapper::Unknown::kNaN : mapper::Unknown::kZero,
                filter_settings);
            const MappedBenchRun run = MapBenchRun(setup, course, sim, 3, params.cas.unknown);
            std::map<std::string, mapper::FilterParams> own;  // preset `pipelines:` sections
            YAML::Emitter extra;  // preset and per-pipeline settings, after the filters
            extra << YAML::BeginMap;
            if (!options.preset.empty()) {
                extra << YAML::Key << "preset" << YAML::Value << options.preset;
            }
            bool any_own = false;
            for (const auto& [pipeline, assignments] : pipeline_settings) {
                if (std::find(options.pipelines.begin(), options.pipelines.end(), pipeline) ==
                    options.pipelines.end()) {
                    continue;  // a section for a pipeline this bench does not score
                }
                own[pipeline] = SetupFilterParams(setup, 3, params.cas.unknown, assignments);
                if (!any_own) {
                    extra << YAML::Key << "pipeline_filter_settings" << YAML::Value
                          << YAML::BeginMap;
                    any_own = true;
                }
                extra << YAML::Key << pipeline << YAML::Value << YAML::Flow << assignments;
            }
            BenchRunRecord record;
            record.has_sheet = keep_maps;
            record.run = ScorePipelines(run, &sim, course, params, options.pipelines,
                                        keep_maps ? &record.sheet : nullptr, own);
            record.run.scene = scene_run ? course.path : std::string();
            record.name = BenchRunName(record.run);
            record.config_yaml = run.config_yaml + FilterParamsYaml(params);
            if (any_own) {
                extra << YAML::EndMap;
            }
            extra << YAML::EndMap;
            if (!options.preset.empty() || any_own) {
                record.config_yaml += io::EmittedText(extra);
            }
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
        result.grids[k] =
            k >= n_courses ? scene_setups[k - n_courses].grid : setups[k % tests.size()].grid;
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
                       (r.scene.empty()
                            ? "obstacle course " + std::to_string(r.course) + ", test " + r.test
                            : "scene " + r.scene + ", motion " + r.test) +
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
    io::WriteTextAtomically(dir / "pipelines.md", PipelinesMarkdown(result.runs));
    const double elapsed =
        result.elapsed_s +
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::string json = BenchJson(result.runs, elapsed, result.threads);
    io::WriteTextAtomically(dir / "bench.json", json);
    return json;
}

std::optional<BenchResult> RunBenchToFolder(BenchOptions options,
                                            const fs::path& out_dir,
                                            const std::string& json_copy,
                                            const core::ProgressFn& progress) {
    options.Validate();  // bad input fails before any work
    CheckBenchOutputFolder(out_dir);
    const DistributedSession session;
    options.session = &session;
    io::OutputSet outputs;  // rank 0 writes every output
    fs::path json_tmp;
    fs::path out_tmp;
    if (session.rank() == 0) {
        if (!json_copy.empty()) {
            json_tmp = outputs.AddFile(json_copy, "json");
        }
        out_tmp = outputs.AddFolder(out_dir, "out");
    }
    BenchResult result = RunBench(options, session.rank() == 0 ? progress : core::ProgressFn{});
    result.ranks = session.ranks();
    if (session.rank() != 0) {
        return std::nullopt;
    }
    const std::string json = WriteBenchOutputs(out_tmp, result);
    if (!json_copy.empty()) {
        io::WriteTextAtomically(json_tmp, json);
    }
    outputs.Publish();
    return result;
}

void CheckBenchOutputFolder(const std::filesystem::path& dir) {
    std::error_code ec;
    if (std::filesystem::is_directory(dir, ec) && !std::filesystem::is_empty(dir, ec) &&
        !std::filesystem::exists(dir / "bench.json", ec)) {
        throw MakeInputError(dir.string(), "out", "",
                             "holds files but no bench.json: not replacing a folder that is not "
                             "a bench output; choose a new or empty folder");
    }
}

}  // namespace casmap::pipeline
