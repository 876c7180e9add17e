#include "casmap/pipeline/bench.hpp"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "casmap/core/input_error.hpp"
#include "casmap/pipeline/bench_runner.hpp"
#include "casmap/pipeline/preset.hpp"
#include "tests/temp_dir.hpp"

namespace casmap::pipeline {
namespace {

/// The InputError `options.Validate()` throws (fails the test if none).
InputError ValidationError(const BenchOptions& options) {
    try {
        options.Validate();
    } catch (const InputError& e) {
        return e;
    }
    ADD_FAILURE() << "expected InputError";
    return InputError("");
}

TEST(BenchOptions, DefaultsAreValid) { EXPECT_NO_THROW(BenchOptions{}.Validate()); }

TEST(BenchOptions, DefaultsArePaperBenchmark) {
    const BenchOptions o;
    EXPECT_EQ(o.courses.size(), 16U);
    EXPECT_EQ(o.tests, (std::vector<std::string>{"T", "TR", "TP", "TRP"}));
    EXPECT_EQ(o.seed, 1U);
}

TEST(BenchOptions, RejectedFieldsAreNamedWithoutFlags) {
    struct Case {
        BenchOptions options;
        std::string field;
        std::string text;
    };
    std::vector<Case> cases(6);
    cases[0].options.courses = {0};
    cases[0].field = "courses";
    cases[1].options.courses = {4, 4};
    cases[1].field = "courses";
    cases[2].options.tests = {"T", "XY"};
    cases[2].field = "tests";
    cases[3].options.courses_dir = "/nonexistent";
    cases[3].field = "courses_dir";
    cases[4].options.filter_settings = {"nope=1"};
    cases[4].text = "nope";
    cases[5].options.tests = {};
    cases[5].field = "tests";
    for (const Case& c : cases) {
        const InputError e = ValidationError(c.options);
        const std::string what = e.what();
        if (!c.field.empty()) {
            EXPECT_EQ(e.field(), c.field) << what;
        }
        EXPECT_NE(what.find(c.text), std::string::npos) << what;
        EXPECT_EQ(what.find("--courses"), std::string::npos) << what;
        EXPECT_EQ(what.find("--tests"), std::string::npos) << what;
    }
}

TEST(ParseCourses, RangesListsAndErrorsNamingTheCallersField) {
    EXPECT_EQ(ParseCourses("1,3,7-9", "courses"), (std::vector<int>{1, 3, 7, 8, 9}));
    EXPECT_EQ(ParseCourses("4,4", "courses"), (std::vector<int>{4}));
    EXPECT_THROW((void)ParseCourses("0", "courses"), InputError);
    try {
        (void)ParseCourses("9-3", "my_field");
        FAIL();
    } catch (const InputError& e) {
        EXPECT_EQ(e.field(), "my_field");
        EXPECT_NE(std::string(e.what()).find("inverted"), std::string::npos);
    }
    EXPECT_EQ(ParseTests("TRP,T", "tests"), (std::vector<std::string>{"T", "TRP"}));
}

// One course x test through the library: the figures do not depend on the thread count,
// progress reaches total, and the report names every filter.
TEST(RunBench, OneRunIsThreadIndependentAndReportsProgress) {
    BenchOptions options;
    options.courses = {4};
    options.tests = {"T"};
    options.seed = 3;
    options.sheets = false;
    options.threads = 1;
    std::vector<std::size_t> seen;
    const BenchResult one = RunBench(options, [&](std::size_t done, std::size_t total) {
        EXPECT_EQ(total, 1U);
        seen.push_back(done);
    });
    EXPECT_EQ(seen, (std::vector<std::size_t>{1}));
    ASSERT_EQ(one.runs.size(), 1U);
    EXPECT_TRUE(one.sheets.empty());
    EXPECT_EQ(one.run_names, (std::vector<std::string>{"course04_T"}));
    EXPECT_NE(one.run_configs[0].find("filters:\n  cas: {k: 2"), std::string::npos);
    const BenchRun& run = one.runs[0];
    EXPECT_EQ(run.course, 4);
    EXPECT_EQ(run.test, "T");
    EXPECT_GT(run.scans, 100);
    for (const std::string& name : BenchFilterNames()) {
        ASSERT_EQ(run.filters.count(name), 1U) << name;
        EXPECT_TRUE(std::isfinite(run.filters.at(name).pi)) << name;
    }
    options.threads = 2;
    const BenchResult two = RunBench(options);
    EXPECT_EQ(BenchJson(one.runs, 0.0, 1), BenchJson(two.runs, 0.0, 1));
}

// Every named pipeline on one run: each reports every field, the paper's five equal a default
// run's figures bit for bit (same beams, same code), and the ones that map again (Kalman,
// pre-filters) see the same scans.
TEST(RunBench, EveryPipelineReportsEveryFieldAndThePaperFiveAreUnchanged) {
    BenchOptions options;
    options.courses = {4};
    options.tests = {"T"};
    options.sheets = false;
    options.threads = 1;
    const BenchResult paper = RunBench(options);
    options.pipelines = AllPipelineNames();
    const BenchResult all = RunBench(options);
    ASSERT_EQ(all.runs.size(), 1U);
    const BenchRun& run = all.runs[0];
    EXPECT_EQ(run.unknown, "zero");
    EXPECT_TRUE(run.scene.empty());
    ASSERT_EQ(run.filters.size(), AllPipelineNames().size());
    for (const std::string& name : AllPipelineNames()) {
        ASSERT_EQ(run.filters.count(name), 1U) << name;
        const FilterScore& f = run.filters.at(name);
        EXPECT_TRUE(std::isfinite(f.pi)) << name;
        EXPECT_GT(f.pi, 0.0) << name;
        EXPECT_TRUE(std::isfinite(f.edge_rmse_m)) << name;
        EXPECT_TRUE(std::isfinite(f.open_rmse_m)) << name;
        EXPECT_EQ(f.coverage, 1.0) << name;  // 0-for-unknown maps: every region cell scored
        EXPECT_EQ(f.cells, 200 * 80) << name;
        ASSERT_EQ(run.poles_kept.count(name), 1U) << name;
    }
    EXPECT_EQ(run.filters.at("raw").pi, 1.0);  // Eq. 11's denominator is the raw map
    EXPECT_NE(run.filters.at("kalman").rmse_m, run.filters.at("raw").rmse_m);
    EXPECT_NE(run.filters.at("range_jump").rmse_m, run.filters.at("raw").rmse_m);
    EXPECT_LT(run.filters.at("sweep_jump").pi, 1.0);  // fewer mixed pixels than the raw map
    EXPECT_NE(run.filters.at("shadow").rmse_m, run.filters.at("raw").rmse_m);
    for (const std::string& name : PaperPipelineNames()) {
        const FilterScore& a = paper.runs[0].filters.at(name);
        const FilterScore& b = run.filters.at(name);
        EXPECT_EQ(a.pi, b.pi) << name;
        EXPECT_EQ(a.rmse_m, b.rmse_m) << name;
        EXPECT_EQ(a.spikes, b.spikes) << name;
        EXPECT_EQ(paper.runs[0].poles_kept.at(name), run.poles_kept.at(name)) << name;
    }
    // bench.json: every pipeline under filters.<name> with every field, in registry order.
    const std::string json = BenchJson(all.runs, 0.0, 1);
    std::size_t at = 0;
    for (const std::string& name : AllPipelineNames()) {
        const std::size_t key = json.find("\"" + name + "\":{\"pi\":", at);
        ASSERT_NE(key, std::string::npos) << name;
        at = key;
        const std::string entry = json.substr(key, json.find('}', key) - key);
        for (const char* field :
             {"\"rmse_m\"", "\"spikes\"", "\"fill_error_m\"", "\"coverage\"", "\"cells\"",
              "\"rmse_edge_m\"", "\"rmse_open_m\"", "\"poles_kept\"", "\"poles\""}) {
            EXPECT_NE(entry.find(field), std::string::npos) << name << " " << field;
        }
    }
    const std::string md = PipelinesMarkdown(all.runs);
    for (const std::string& name : AllPipelineNames()) {
        EXPECT_NE(md.find("| " + name + " | "), std::string::npos) << name;
    }
    // The paper's PI table keeps the paper's five columns only.
    EXPECT_EQ(PiTable(all.runs), PiTable(paper.runs));
}

// A terrain scene through BenchOptions::scenes: unknown cells NaN, the truth keeps heights
// below the datum, RMSEs over observed cells, poles of the scene counted.
TEST(RunBench, TerrainSceneRunsWithNanUnknownCells) {
    const casmap::test::TempDir tmp("bench_slope");
    const std::filesystem::path scene = tmp / "casmap_bench_slope.yaml";
    std::ofstream(scene) << "objects:\n"
                            "  - name: slope\n"
                            "    box: {size_m: [8, 4, 0.2]}\n"
                            "    pose: {xyz_m: [3.5, 0, -0.16], rpy_deg: [0, 2, 0]}\n"
                            "    reflectivity: 0.3\n"
                            "    terrain: true\n"
                            "  - name: rock\n"
                            "    box: {size_m: [0.3, 0.3, 0.2]}\n"
                            "    pose: {xyz_m: [3, 0.3, 0.0], rpy_deg: [0, 0, 0]}\n"
                            "    reflectivity: 0.5\n"
                            "  - name: pole1\n"
                            "    cylinder: {radius_m: 0.012, height_m: 0.914}\n"
                            "    pose: {xyz_m: [4.0125, -0.5125, 0.4], rpy_deg: [0, 0, 0]}\n"
                            "    reflectivity: 0.45\n";
    BenchOptions options;
    options.courses = {};
    options.scenes = {scene.string()};
    options.scene_motions = {"T"};
    options.pipelines = {"cas", "raw", "cas_terrain", "kalman", "range_jump_median"};
    options.sheets = true;
    options.threads = 2;
    const BenchResult result = RunBench(options);
    ASSERT_EQ(result.runs.size(), 1U);
    const BenchRun& run = result.runs[0];
    EXPECT_EQ(result.run_names[0], "casmap_bench_slope_T");
    EXPECT_EQ(run.scene, scene.string());
    EXPECT_EQ(run.course, 0);
    EXPECT_EQ(run.unknown, "nan");
    EXPECT_EQ(run.poles, (std::vector<std::string>{"pole1"}));
    EXPECT_NE(result.run_configs[0].find("unknown: nan"), std::string::npos);
    // Truth below the datum kept; raw map NaN where never observed.
    const SheetMaps& maps = result.sheets[0];
    const float lowest = *std::min_element(maps.truth.data.begin(), maps.truth.data.end());
    EXPECT_LT(lowest, -0.05F);
    std::size_t unknown = 0;
    for (std::size_t i = 0; i < maps.raw.data.size(); ++i) {
        if (maps.certainty.data[i] == 0.0F) {
            EXPECT_TRUE(std::isnan(maps.raw.data[i])) << i;
            ++unknown;
        }
    }
    EXPECT_GT(unknown, 0U);
    const FilterScore& raw = run.filters.at("raw");
    EXPECT_EQ(raw.coverage, 1.0);
    EXPECT_LT(raw.cells, 200 * 80);  // observed cells only
    EXPECT_GT(raw.cells, 1000);
    EXPECT_TRUE(std::isfinite(raw.rmse_m));
    EXPECT_LT(raw.rmse_m, 0.1);  // the slope is mapped at its height, not pulled to 0
    for (const std::string& name : options.pipelines) {
        const FilterScore& f = run.filters.at(name);
        EXPECT_TRUE(std::isfinite(f.rmse_m)) << name;
        EXPECT_GT(f.coverage, 0.5) << name;
        EXPECT_LE(f.coverage, 1.0 + 1e-12) << name;
    }
    const std::string json = BenchJson(result.runs, 0.0, 1);
    EXPECT_NE(json.find("\"scene\":"), std::string::npos);
    EXPECT_NE(json.find("\"unknown\":\"nan\""), std::string::npos);
    EXPECT_NE(PipelinesMarkdown(result.runs).find("Scene casmap_bench_slope_T"), std::string::npos);
}

TEST(BenchOptions, PipelinesScenesAndPresetsAreValidated) {
    BenchOptions o;
    o.pipelines = {"cas", "nope"};
    EXPECT_EQ(ValidationError(o).field(), "pipelines");
    o = BenchOptions{};
    o.pipelines = {};
    EXPECT_EQ(ValidationError(o).field(), "pipelines");
    o = BenchOptions{};
    o.scenes = {"/nonexistent/scene.yaml"};
    EXPECT_EQ(ValidationError(o).field(), "scenes");
    o = BenchOptions{};
    o.courses = {};
    EXPECT_EQ(ValidationError(o).field(), "courses");  // neither courses nor scenes
    o = BenchOptions{};
    o.preset = "no_such_preset";
    EXPECT_EQ(ValidationError(o).field(), "preset");
    o = BenchOptions{};
    o.preset = "paper";
    o.filter_settings = {"A=30"};
    EXPECT_NO_THROW(o.Validate());
    const std::vector<std::string> settings = o.EffectiveFilterSettings();
    ASSERT_FALSE(settings.empty());
    EXPECT_EQ(settings.back(), "A=30");  // --set after the preset
}

// A preset's `pipelines:` section tunes one pipeline only: the others keep the shared values,
// the tuned one equals a bench where the whole run had those values; --set overrides both.
TEST(RunBench, PresetPipelineSectionsApplyToTheirPipelineOnly) {
    const casmap::test::TempDir tmp("bench_own_preset");
    const std::filesystem::path file = tmp / "casmap_bench_own_preset.yaml";
    std::ofstream(file) << "set: {}\npipelines:\n  cas_trail: {A: 25, support_min: 9}\n"
                           "  kalman_median: {window: 7}\n";
    BenchOptions options;
    options.courses = {4};
    options.tests = {"T"};
    options.sheets = false;
    options.threads = 2;
    options.pipelines = {"cas", "cas_trail", "median", "kalman_median"};
    const BenchResult plain = RunBench(options);
    options.preset = file.string();
    const BenchResult own = RunBench(options);
    BenchOptions all = options;
    all.preset.clear();
    all.filter_settings = {"A=25", "support_min=9", "window=7"};
    const BenchResult global = RunBench(all);
    const auto pi = [](const BenchResult& r, const std::string& name) {
        return r.runs[0].filters.at(name).pi;
    };
    EXPECT_EQ(pi(own, "cas"), pi(plain, "cas"));
    EXPECT_EQ(pi(own, "median"), pi(plain, "median"));
    EXPECT_EQ(pi(own, "cas_trail"), pi(global, "cas_trail"));
    EXPECT_EQ(pi(own, "kalman_median"), pi(global, "kalman_median"));
    EXPECT_NE(pi(own, "cas_trail"), pi(plain, "cas_trail"));
    EXPECT_NE(pi(own, "kalman_median"), pi(plain, "kalman_median"));
    EXPECT_EQ(own.runs[0].cas_classes.all.removed_pct, plain.runs[0].cas_classes.all.removed_pct);
    EXPECT_NE(own.run_configs[0].find("pipeline_filter_settings:\n  cas_trail: [A=25, "
                                      "support_min=9]"),
              std::string::npos)
        << own.run_configs[0];
    // --set comes last for every pipeline, sections included.
    options.filter_settings = {"A=25", "support_min=9", "window=7"};
    const BenchResult both = RunBench(options);
    EXPECT_EQ(pi(both, "cas"), pi(global, "cas"));
    EXPECT_EQ(pi(both, "cas_trail"), pi(global, "cas_trail"));
}

// A preset section sets a pre-filter / Kalman parameter for one pipeline: that pipeline's map is
// made with it (its figures equal a bench with the value for every pipeline), the pipelines
// sharing the stage without a section keep the defaults, and the run's configuration shows it.
TEST(RunBench, PresetSectionsSetPreFilterAndKalmanParameters) {
    const casmap::test::TempDir tmp("bench_stage_preset");
    const std::filesystem::path file = tmp / "casmap_bench_stage_preset.yaml";
    std::ofstream(file) << "set: {}\npipelines:\n  shadow_cas: {shadow.min_angle_deg: 25}\n"
                           "  kalman_median: {kalman.mahalanobis_gate: 1.0}\n";
    BenchOptions options;
    options.courses = {4};
    options.tests = {"T"};
    options.sheets = false;
    options.threads = 2;
    options.pipelines = {"cas", "kalman", "kalman_median", "shadow", "shadow_cas"};
    const BenchResult plain = RunBench(options);
    options.preset = file.string();
    const BenchResult own = RunBench(options);
    BenchOptions all = options;
    all.preset.clear();
    all.filter_settings = {"shadow.min_angle_deg=25", "kalman.mahalanobis_gate=1.0"};
    const BenchResult global = RunBench(all);
    const auto score = [](const BenchResult& r, const std::string& name) {
        const FilterScore& f = r.runs[0].filters.at(name);
        return std::make_tuple(f.pi, f.rmse_m, f.spikes, f.coverage);
    };
    EXPECT_EQ(score(own, "shadow_cas"), score(global, "shadow_cas"));
    EXPECT_NE(std::get<0>(score(own, "shadow_cas")), std::get<0>(score(plain, "shadow_cas")));
    EXPECT_EQ(score(own, "shadow"), score(plain, "shadow"));  // no section: default angle
    EXPECT_NE(score(global, "shadow"), score(plain, "shadow"));
    EXPECT_EQ(score(own, "kalman_median"), score(global, "kalman_median"));
    EXPECT_NE(std::get<0>(score(own, "kalman_median")), std::get<0>(score(plain, "kalman_median")));
    EXPECT_EQ(score(own, "kalman"), score(plain, "kalman"));
    EXPECT_EQ(score(own, "cas"), score(plain, "cas"));
    EXPECT_NE(own.run_configs[0].find("pipeline_filter_settings:\n  kalman_median: "
                                      "[kalman.mahalanobis_gate=1.0]\n  shadow_cas: "
                                      "[shadow.min_angle_deg=25]"),
              std::string::npos)
        << own.run_configs[0];
    // --set for every pipeline: the run's effective filters section holds the values.
    const YAML::Node config = YAML::Load(global.run_configs[0]);
    EXPECT_EQ(config["filters"]["shadow"]["min_angle_deg"].as<double>(), 25.0);
    EXPECT_EQ(config["filters"]["kalman"]["mahalanobis_gate"].as<double>(), 1.0);
    EXPECT_EQ(config["filters"]["range_jump"]["jump_min_m"].as<double>(),
              mapper::RangeJumpConfig{}.jump_min_m);
}

// A bad stage value in a preset section names the file, the section and the parameter.
TEST(LoadPreset, BadStageValueNamesTheSectionAndParameter) {
    const casmap::test::TempDir tmp("bad_stage_preset");
    const std::filesystem::path file = tmp / "casmap_bad_stage_preset.yaml";
    std::ofstream(file) << "set: {}\npipelines:\n  range_jump_cas: {range_jump.jump_min_m: -1}\n";
    try {
        (void)LoadPreset(file.string());
        ADD_FAILURE() << "accepted range_jump.jump_min_m = -1";
    } catch (const InputError& e) {
        EXPECT_EQ(e.field(), "pipelines.range_jump_cas.range_jump.jump_min_m") << e.what();
        EXPECT_NE(std::string(e.what()).find(file.string() + ":3:"), std::string::npos) << e.what();
        EXPECT_NE(e.rule().find("allowed: > 0"), std::string::npos) << e.what();
    }
    BenchOptions o;
    o.filter_settings = {"range_jump.jump_min_m=0.04"};  // default margin 0.03 >= 0.04 / 2
    try {
        o.Validate();
        ADD_FAILURE() << "accepted range_jump margin 0.03 with jump_min_m 0.04";
    } catch (const InputError& e) {
        EXPECT_EQ(e.field(), "range_jump.margin_m") << e.what();
    }
}

// The paper preset gives the defaults' effective parameters, byte for byte.
TEST(BenchOptions, PaperPresetEqualsTheDefaults) {
    BenchOptions o;
    o.preset = "paper";
    mapper::FilterParams with;
    for (const std::string& s : o.EffectiveFilterSettings()) {
        with.SetAssignment(s);
    }
    EXPECT_EQ(FilterParamsYaml(with), FilterParamsYaml(mapper::FilterParams{}));
}

TEST(RunBenchToFolder, SwapsInTheOutputsAndTheJsonCopy) {
    const casmap::test::TempDir tmp("pipeline_bench_folder");
    const std::filesystem::path& dir = tmp.Path();
    std::filesystem::create_directories(dir / "not_a_bench");
    std::ofstream(dir / "not_a_bench" / "notes.txt") << "mine";
    BenchOptions options;
    options.courses = {4};
    options.tests = {"T"};
    options.sheets = false;
    options.threads = 1;
    const std::optional<BenchResult> r =
        RunBenchToFolder(options, dir / "out", (dir / "copy.json").string());
    ASSERT_TRUE(r.has_value());  // one rank without mpirun
    EXPECT_EQ(r->ranks, 1);
    ASSERT_EQ(r->runs.size(), 1U);
    std::ifstream a(dir / "out" / "bench.json");
    std::ifstream b(dir / "copy.json");
    const std::string written((std::istreambuf_iterator<char>(a)), {});
    const std::string copy((std::istreambuf_iterator<char>(b)), {});
    EXPECT_FALSE(written.empty());
    EXPECT_EQ(written, copy);
    // A folder that holds other files is not replaced: InputError before any work.
    try {
        (void)RunBenchToFolder(options, dir / "not_a_bench", "");
        ADD_FAILURE() << "no InputError";
    } catch (const InputError& e) {
        EXPECT_EQ(e.field(), "out");
        EXPECT_EQ(e.where(), (dir / "not_a_bench").string());
    }
    EXPECT_TRUE(std::filesystem::exists(dir / "not_a_bench" / "notes.txt"));
}

}  // namespace
}  // namespace casmap::pipeline
