// casmap sweep [--set NAME=FROM:TO:STEP]... [--fix NAME=VALUE]... [--courses ...]
//              [--tests ...] [--seed N] [--json FILE] [--out DIR] [--sensor LMS200.yaml]
// A grid over CAS parameters (A, G, B, h_sum_min, a, E, k) and the table speed
// (pipeline::RunSweep): the mean and spread of CAS's PI (Eq. 11) per grid point. Outputs (DIR,
// default out/sweep): sweep.json, runs/*.yaml and, for two swept parameters, heatmap.png.
#include <cstdio>
#include <memory>
#include <string>

#include "apps/casmap/commands.hpp"
#include "apps/casmap/flag_names.hpp"
#include "apps/casmap/progress_bar.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/io/atomic_file.hpp"
#include "casmap/mapper/filter_params.hpp"
#include "casmap/pipeline/bench_runner.hpp"
#include "casmap/pipeline/sweep.hpp"

namespace casmap::app {
namespace {

struct SweepFlags {
    std::vector<std::string> set;
    std::string courses = "1-16";
    std::string tests = "T";
    std::string json;
    std::string out = "out/sweep";
    pipeline::SweepOptions options;
};

const FlagNames kFlags = {{"axes", "--set"},
                          {"fixed", "--fix"},
                          {"courses", "--courses"},
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
    opt.courses = pipeline::ParseCourses(flags.courses, "--courses");
    opt.tests = pipeline::ParseTests(flags.tests, "--tests");
    opt.threads = common.threads;
    for (const std::string& fixed : opt.fixed) {  // name the flag the user wrote, not --set
        try {
            mapper::FilterParams check;
            check.SetAssignment(fixed);
        } catch (const InputError& e) {
            std::string message = e.what();
            if (message.rfind("--set", 0) == 0) {
                message.replace(0, 5, "--fix");
            }
            throw InputError(message);
        }
    }
    opt.Validate();  // bad input exits 2 before any work
    if (!flags.json.empty()) {
        pipeline::CheckWritableFile(flags.json, "--json");
    }
    io::EnsureDirectory(flags.out);
    pipeline::SweepResult result;
    {
        ProgressBar bar("sweep");
        result = pipeline::RunSweep(opt, bar.Fn());
    }
    const std::string json = pipeline::WriteSweepOutputs(flags.out, result);
    if (!flags.json.empty()) {
        io::WriteTextAtomically(flags.json, json);
    }
    std::fputs(pipeline::SweepTable(result).c_str(), stdout);
    std::printf("%zu point(s) x %zu run(s) in %.1f s on %d threads -> %s\n", result.points.size(),
                result.run_names.size(), result.elapsed_s, result.threads, flags.out.c_str());
}

}  // namespace

void AddSweepCommand(CLI::App& app, CommonOptions& common) {
    auto flags = std::make_shared<SweepFlags>();
    pipeline::SweepOptions& opt = flags->options;
    CLI::App* sub = app.add_subcommand(
        "sweep", "Grid over CAS parameters and speed: mean and spread of PI per point");
    sub->add_option("--set", flags->set,
                    "NAME=FROM:TO:STEP, NAME in A, G, B, h_sum_min, a, E, k, speed; repeatable");
    sub->add_option("--fix", opt.fixed, "fixed filter parameter NAME=VALUE; repeatable");
    sub->add_option("--courses", flags->courses, "courses, e.g. 1-16, 4 or 1,4,7-9")
        ->capture_default_str();
    sub->add_option("--tests", flags->tests, "tests: T,TR,TP,TRP")->capture_default_str();
    sub->add_option("--seed", opt.seed, "simulator seed (every run)")->capture_default_str();
    sub->add_option("--json", flags->json, "also write sweep.json here");
    sub->add_option("--out", flags->out, "output directory (sweep.json, heat map, configs)")
        ->capture_default_str();
    sub->add_option("--courses-dir", opt.courses_dir,
                    "directory of course01.yaml .. course16.yaml (default: scenes/courses)");
    sub->add_option("--rig", opt.rig_path, "rig YAML (table settings; default: the paper course)");
    sub->add_option("--sensor", opt.sensor_path,
                    "LMS 200 YAML (config/lms200.yaml; default: the built-in config)");
    AddThreadsOption(sub, common);
    sub->callback([flags, &common] { WithFlagNames(kFlags, [&] { RunSweep(*flags, common); }); });
}

}  // namespace casmap::app
