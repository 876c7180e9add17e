// casmap sweep [--set NAME=FROM:TO:STEP]... [--fix NAME=VALUE]... [--filter cas|cas_trail|...]
//              [--courses|--train-courses ...] [--seed N|--train-seeds ...] [--test-seeds ...]
//              [--test-courses ...] [--grow N] [--tests ...] [--json FILE] [--out DIR] ...
// A grid over CAS (or variant) parameters and the table speed (pipeline::RunSweep): PI, spikes
// and poles per point on training runs, the best point scored on held-out runs. Outputs (DIR,
// default out/sweep; rank 0 under mpirun): sweep.json, runs/*.yaml, heatmap.png (2 axes).
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "apps/casmap/commands.hpp"
#include "apps/casmap/flag_names.hpp"
#include "apps/casmap/progress_bar.hpp"
#include "casmap/pipeline/bench_runner.hpp"
#include "casmap/pipeline/sweep.hpp"

namespace casmap::app {
namespace {

struct SweepFlags {
    std::vector<std::string> set;
    std::string courses = "1-16";
    std::string train_courses;
    std::string train_seeds;
    std::string test_seeds;
    std::string test_courses;
    std::string tests = "T";
    std::string json;
    std::string out = "out/sweep";
    pipeline::SweepOptions options;
};

const FlagNames kFlags = {{"axes", "--set"},
                          {"fixed", "--fix"},
                          {"courses", "--courses"},
                          {"filter", "--filter"},
                          {"seeds", "--train-seeds"},
                          {"test_seeds", "--test-seeds"},
                          {"test_courses", "--test-courses"},
                          {"grow", "--grow"},
                          {"search", "--search"},
                          {"tests", "--tests"},
                          {"courses_dir", "--courses-dir"},
                          {"rig_path", "--rig"},
                          {"sensor_path", "--sensor"},
                          {"threads", "--threads"}};

void RunSweep(SweepFlags& flags, const CommonOptions& common) {
    pipeline::SweepOptions& opt = flags.options;
    for (const std::string& s : flags.set) {
        opt.axes.push_back(pipeline::ParseSweepAxis(s, "--set"));
    }
    opt.courses = flags.train_courses.empty()
                      ? pipeline::ParseCourses(flags.courses, "--courses")
                      : pipeline::ParseCourses(flags.train_courses, "--train-courses");
    if (!flags.train_seeds.empty()) {
        opt.seeds = pipeline::ParseSeeds(flags.train_seeds, "--train-seeds");
    }
    if (!flags.test_seeds.empty()) {
        opt.test_seeds = pipeline::ParseSeeds(flags.test_seeds, "--test-seeds");
    }
    if (!flags.test_courses.empty()) {
        opt.test_courses = pipeline::ParseCourses(flags.test_courses, "--test-courses");
    }
    opt.tests = pipeline::ParseTests(flags.tests, "--tests");
    opt.threads = common.threads;
    std::optional<pipeline::SweepResult> result;
    {
        ProgressBar bar("sweep");
        WithCommandLineFlags(
            {{"json", "--json"}},
            [&] { result = pipeline::RunSweepToFolder(opt, flags.out, flags.json, bar.Fn()); },
            {{"json", flags.json}});
    }
    if (!result) {
        return;  // not rank 0: rank 0 printed and wrote everything
    }
    std::fputs(pipeline::SweepTable(*result).c_str(), stdout);
    std::printf(
        "%zu point(s) x %zu training run(s) + %zu held-out in %.1f s on %d threads x %d "
        "rank(s) -> %s\n",
        result->points.size(), result->run_names.size(), result->held_out.size(), result->elapsed_s,
        result->threads, result->ranks, flags.out.c_str());
}

}  // namespace

void AddSweepCommand(CLI::App& app, CommonOptions& common) {
    auto flags = std::make_shared<SweepFlags>();
    pipeline::SweepOptions& opt = flags->options;
    CLI::App* sub = app.add_subcommand(
        "sweep", "Grid over CAS parameters and speed: mean and spread of PI per point");
    std::string axes = "NAME=FROM:TO:STEP with NAME in";  // the library's list, never stale
    for (const std::string& name : pipeline::SweepableParameters()) {
        axes += " " + name;
    }
    sub->add_option("--set", flags->set,
                    axes +
                        " (shadow.*, range_jump.*, sweep_jump.*, kalman.*, consensus.* with a "
                        "pipeline "
                        "running them; docs/commands/sweep.md); repeatable");
    sub->add_option("--fix", opt.fixed, "fixed filter parameter NAME=VALUE; repeatable");
    sub->add_option("--courses", flags->courses, "training courses, e.g. 1-16, 4 or 1,4,7-9")
        ->capture_default_str();
    sub->add_option("--train-courses", flags->train_courses, "the same as --courses")
        ->excludes(sub->get_option("--courses"));
    sub->add_option("--filter", opt.filter,
                    "pipeline to tune: cas, cas_trail, cas_terrain or any casmap bench pipeline")
        ->capture_default_str();
    sub->add_option("--train-seeds", flags->train_seeds,
                    "training seeds, e.g. 1-2 or 1,5 (default: --seed)");
    sub->add_option("--test-seeds", flags->test_seeds,
                    "held-out seeds scoring the chosen point (default: the training seeds)");
    sub->add_option("--test-courses", flags->test_courses,
                    "held-out courses (default: the training courses)");
    sub->add_option("--search", opt.search,
                    "grid (every point) or descent (coordinate descent over the axes' values)")
        ->capture_default_str();
    sub->add_option("--grow", opt.grow,
                    "growth rounds: extend an axis while the best point sits on its edge (0..20)")
        ->capture_default_str();
    sub->add_option("--tests", flags->tests, "tests: T,TR,TP,TRP")->capture_default_str();
    sub->add_option("--seed", opt.seed, "simulator seed of the training runs")
        ->capture_default_str();
    sub->add_option("--json", flags->json, "also write sweep.json here");
    sub->add_option("--out", flags->out, "output directory (sweep.json, heat map, configs)")
        ->capture_default_str();
    sub->add_option("--courses-dir", opt.courses_dir,
                    "directory of course01.yaml .. course16.yaml (default: scenes/courses)");
    sub->add_option("--rig", opt.rig_path, "rig YAML (table settings; default: the paper course)");
    sub->add_option("--sensor", opt.sensor_path,
                    "LMS 200 YAML (config/lms200.yaml; default: the built-in config)");
    AddThreadsOption(sub, common);
    sub->callback([flags, &common] {
        WithWhereAsFlag("filter parameters", "--fix",
                        [&] { WithFlagNames(kFlags, [&] { RunSweep(*flags, common); }); });
    });
}

}  // namespace casmap::app
