// casmap bench [--courses 1-16] [--tests T,TR,TP,TRP] [--seed N] [--out DIR] [--json FILE]
//              [--rig RIG.yaml] [--sensor LMS200.yaml] [--set NAME=VALUE]... [--no-sheets] [--maps]
//              [--pipelines LIST|all] [--scenes A.yaml,B.yaml --motion vehicle] [--preset NAME]
// The paper's benchmark (pipeline::RunBench): every course x test simulated, mapped, filtered
// by CAS and the four baselines and scored against the exact ground truth.
// Outputs (DIR, default out/bench): bench.json, pi_chart.png (Fig. 8), table2.md (Table II),
// poles.md, pi_table.txt, sheets/courseNN_TEST.png (Fig. 7), runs/courseNN_TEST.yaml; with
// --maps also runs/courseNN_TEST/*.tif + maps.json (pipeline/bench_maps.hpp, for casmap view).
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "apps/casmap/commands.hpp"
#include "apps/casmap/flag_names.hpp"
#include "apps/casmap/progress_bar.hpp"
#include "casmap/core/text.hpp"
#include "casmap/pipeline/bench.hpp"
#include "casmap/pipeline/bench_runner.hpp"

namespace casmap::app {
namespace {

struct BenchFlags {
    std::string courses = "1-16";
    std::string tests = "T,TR,TP,TRP";
    std::string out = "out/bench";
    std::string json;
    bool no_sheets = false;
    bool maps = false;      // --maps: runs/<run>/*.tif + maps.json for casmap view
    std::string pipelines;  // empty: the paper's five
    std::string scenes;
    std::string motion = "vehicle";
    pipeline::BenchOptions options;
};

const FlagNames kFlags = {
    {"courses", "--courses"},      {"tests", "--tests"},         {"courses_dir", "--courses-dir"},
    {"rig_path", "--rig"},         {"sensor_path", "--sensor"},  {"filter_settings", "--set"},
    {"threads", "--threads"},      {"pipelines", "--pipelines"}, {"scenes", "--scenes"},
    {"scene_motions", "--motion"}, {"preset", "--preset"}};

void RunBench(BenchFlags& flags, const CommonOptions& common, bool courses_given) {
    pipeline::BenchOptions& opt = flags.options;
    if (!flags.scenes.empty()) {
        opt.scenes = core::SplitList(flags.scenes);
        opt.scene_motions = core::SplitList(flags.motion);
    }
    // With --scenes the paper's courses run only when --courses is given.
    opt.courses = !flags.scenes.empty() && !courses_given
                      ? std::vector<int>{}
                      : pipeline::ParseCourses(flags.courses, "--courses");
    if (!flags.pipelines.empty()) {
        opt.pipelines = pipeline::ParsePipelines(flags.pipelines, "--pipelines");
    }
    opt.tests = pipeline::ParseTests(flags.tests, "--tests");
    opt.sheets = !flags.no_sheets;
    opt.maps = flags.maps;
    opt.threads = common.threads;
    // The output folder is one set (runs/, sheets/, images, bench.json): filled under a
    // temporary name and swapped in at the end; only a bench folder (or an empty one) is replaced.
    std::optional<pipeline::BenchResult> result;
    {
        ProgressBar bar("bench");
        WithCommandLineFlags(
            {{"out", "--out"}, {"json", "--json"}},
            [&] { result = pipeline::RunBenchToFolder(opt, flags.out, flags.json, bar.Fn()); },
            {{"out", flags.out}, {"json", flags.json}});
    }
    if (!result) {
        return;  // not rank 0: rank 0 writes every output
    }
    std::fputs(pipeline::PiTable(result->runs).c_str(), stdout);
    if (!flags.pipelines.empty() || !opt.scenes.empty()) {
        std::fputs(("\n" + pipeline::PipelinesMarkdown(result->runs)).c_str(), stdout);
    }
    std::printf("%zu runs in %.1f s on %d threads x %d rank(s) -> %s\n", result->runs.size(),
                result->elapsed_s, result->threads, result->ranks, flags.out.c_str());
}

}  // namespace

void AddBenchCommand(CLI::App& app, CommonOptions& common) {
    auto flags = std::make_shared<BenchFlags>();
    pipeline::BenchOptions& opt = flags->options;
    CLI::App* sub = app.add_subcommand(
        "bench", "The paper's benchmark: 16 courses x T/TR/TP/TRP, CAS vs four baselines");
    sub->add_option("--courses", flags->courses, "courses, e.g. 1-16, 4 or 1,4,7-9")
        ->capture_default_str();
    sub->add_option("--tests", flags->tests, "tests: T,TR,TP,TRP")->capture_default_str();
    sub->add_option("--seed", opt.seed, "simulator seed (every run)")->capture_default_str();
    sub->add_option("--out", flags->out, "output directory")->capture_default_str();
    sub->add_option("--json", flags->json, "also write bench.json here");
    sub->add_option("--courses-dir", opt.courses_dir,
                    "directory of course01.yaml .. course16.yaml (default: scenes/courses)");
    sub->add_option("--rig", opt.rig_path, "rig YAML (table settings; default: the paper course)");
    sub->add_option("--sensor", opt.sensor_path,
                    "LMS 200 YAML (config/lms200.yaml; default: the built-in config)");
    sub->add_option("--set", opt.filter_settings,
                    "filter parameter NAME=VALUE (see casmap filter), or a pre-filter's / the "
                    "mapper modes' shadow.*, range_jump.*, sweep_jump.*, kalman.*, consensus.* "
                    "(docs/commands/bench.md)");
    sub->add_option("--pipelines", flags->pipelines,
                    "named pipelines to score, comma list or all (default: the paper's five: "
                    "cas,wiener,average,median,cwm; docs/commands/bench.md)");
    sub->add_option("--scenes", flags->scenes,
                    "further scene YAMLs (comma list), e.g. scenes/outdoor.yaml; unknown cells "
                    "NaN; the courses then run only with --courses");
    sub->add_option("--motion", flags->motion, "motions of the --scenes runs: vehicle, T, ...")
        ->capture_default_str();
    sub->add_option("--preset", opt.preset,
                    "filter-parameter preset: config/presets/NAME.yaml (paper, tuned) or a "
                    "file; --set overrides it");
    sub->add_flag("--no-sheets", flags->no_sheets, "skip the per-run Fig. 7 sheets");
    sub->add_flag("--maps", flags->maps,
                  "also write each run's maps as float TIFFs (runs/<run>/, for casmap view)");
    CLI::Option* courses = sub->get_option("--courses");
    AddThreadsOption(sub, common);
    sub->callback([flags, &common, courses] {
        WithSetFlag([&] {
            WithFlagNames(kFlags, [&] { RunBench(*flags, common, courses->count() > 0); });
        });
    });
}

}  // namespace casmap::app
