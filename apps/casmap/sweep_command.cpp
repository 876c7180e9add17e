// casmap sweep [--set NAME=FROM:TO:STEP]... [--fix NAME=VALUE]... [--courses ...]
//              [--tests ...] [--seed N] [--json FILE] [--out DIR] [--sensor LMS200.yaml]
// A grid over CAS parameters (A, G, B, h_sum_min, a, E, k) and the table speed on chosen
// courses and tests: the mean and spread of CAS's PI (Eq. 11) per grid point. Every course x
// test x speed is simulated once; `a` re-maps the simulated scans, every other parameter only
// re-runs the filter. Two swept parameters also give a heat map PNG.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
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

const std::vector<std::string> kSweepable = {"A", "G", "B", "h_sum_min", "a", "E", "k", "speed"};
constexpr std::size_t kMaxPoints = 10000;

struct SweepOptions {
    std::vector<std::string> set;
    std::vector<std::string> fix;
    std::string courses = "1-16";
    std::string tests = "T";
    std::uint64_t seed = 1;
    std::string json;
    std::string out = "out/sweep";
    std::string courses_dir;
    std::string rig;
    std::string sensor;  // --sensor: LMS 200 YAML
};

struct Axis {
    std::string name;
    std::vector<double> values;
};

double ParseNumber(const std::string& text, const std::string& assignment) {
    std::size_t used = 0;
    double v = 0.0;
    try {
        v = std::stod(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used != text.size() || text.empty() || !std::isfinite(v)) {
        throw MakeInputError("", "--set", assignment, "FROM, TO and STEP must be numbers");
    }
    return v;
}

/// "NAME=FROM:TO:STEP" -> FROM, FROM + STEP, ... <= TO.
Axis ParseAxis(const std::string& assignment) {
    const std::size_t eq = assignment.find('=');
    const std::string rule = "expected NAME=FROM:TO:STEP with FROM <= TO and STEP > 0";
    if (eq == std::string::npos) {
        throw MakeInputError("", "--set", assignment, rule);
    }
    Axis axis;
    axis.name = assignment.substr(0, eq);
    if (std::find(kSweepable.begin(), kSweepable.end(), axis.name) == kSweepable.end()) {
        throw MakeInputError("", "--set", axis.name,
                             "unknown parameter; allowed: A, G, B, h_sum_min, a, E, k, speed");
    }
    const std::string range = assignment.substr(eq + 1);
    const std::size_t c1 = range.find(':');
    const std::size_t c2 = c1 == std::string::npos ? c1 : range.find(':', c1 + 1);
    if (c2 == std::string::npos || range.find(':', c2 + 1) != std::string::npos) {
        throw MakeInputError("", "--set", assignment, rule);
    }
    const double from = ParseNumber(range.substr(0, c1), assignment);
    const double to = ParseNumber(range.substr(c1 + 1, c2 - c1 - 1), assignment);
    const double step = ParseNumber(range.substr(c2 + 1), assignment);
    if (!(step > 0.0)) {
        throw MakeInputError("", "--set", assignment, "STEP must be > 0 (" + rule + ")");
    }
    if (from > to) {
        throw MakeInputError("", "--set", assignment, "inverted range: FROM > TO (" + rule + ")");
    }
    const double count = std::floor((to - from) / step * (1.0 + 1e-12) + 1e-9) + 1.0;
    if (count > static_cast<double>(kMaxPoints)) {
        throw MakeInputError("", "--set", assignment, "more than 10000 values");
    }
    for (int i = 0; i < static_cast<int>(count); ++i) {
        axis.values.push_back(from + i * step);
    }
    return axis;
}

/// The filter overrides of one grid point (NAME=VALUE for FilterParams::Set).
std::vector<std::string> PointOverrides(const std::vector<std::string>& fixed,
                                        const std::vector<Axis>& axes,
                                        const std::vector<double>& point) {
    std::vector<std::string> out = fixed;
    for (std::size_t i = 0; i < axes.size(); ++i) {
        if (axes[i].name == "speed") {
            continue;  // a rig setting; CAS's v follows the run (RunFilterParams)
        }
        out.push_back(axes[i].name + "=" + FormatNumber(point[i]));
        if (axes[i].name == "E") {
            out.push_back("e_term=on");  // sweeping E means using Eq. 10's E term
        }
    }
    return out;
}

struct Stats {
    double mean = std::nan("");
    double std = std::nan("");
    double min = std::nan("");
    double max = std::nan("");
    std::size_t runs = 0;
};

Stats Summarise(const std::vector<double>& v) {
    Stats s;
    std::vector<double> finite;
    for (const double x : v) {
        if (std::isfinite(x)) {
            finite.push_back(x);
        }
    }
    s.runs = finite.size();
    if (finite.empty()) {
        return s;
    }
    double sum = 0.0;
    for (const double x : finite) {
        sum += x;
    }
    s.mean = sum / static_cast<double>(finite.size());
    double ss = 0.0;
    for (const double x : finite) {
        ss += (x - s.mean) * (x - s.mean);
    }
    s.std = std::sqrt(ss / static_cast<double>(finite.size()));  // population spread
    s.min = *std::min_element(finite.begin(), finite.end());
    s.max = *std::max_element(finite.begin(), finite.end());
    return s;
}

void RunSweep(const SweepOptions& opt, const CommonOptions& common);

}  // namespace

void AddSweepCommand(CLI::App& app, CommonOptions& common) {
    auto opt = std::make_shared<SweepOptions>();
    CLI::App* sub = app.add_subcommand(
        "sweep", "Grid over CAS parameters and speed: mean and spread of PI per point");
    sub->add_option("--set", opt->set,
                    "NAME=FROM:TO:STEP, NAME in A, G, B, h_sum_min, a, E, k, speed; repeatable");
    sub->add_option("--fix", opt->fix, "fixed filter parameter NAME=VALUE; repeatable");
    sub->add_option("--courses", opt->courses, "courses, e.g. 1-16, 4 or 1,4,7-9")
        ->capture_default_str();
    sub->add_option("--tests", opt->tests, "tests: T,TR,TP,TRP")->capture_default_str();
    sub->add_option("--seed", opt->seed, "simulator seed (every run)")->capture_default_str();
    sub->add_option("--json", opt->json, "also write sweep.json here");
    sub->add_option("--out", opt->out, "output directory (sweep.json, heat map, configs)")
        ->capture_default_str();
    sub->add_option("--courses-dir", opt->courses_dir,
                    "directory of course01.yaml .. course16.yaml (default: scenes/courses)");
    sub->add_option("--rig", opt->rig, "rig YAML (table settings; default: the paper course)");
    sub->add_option("--sensor", opt->sensor,
                    "LMS 200 YAML (config/lms200.yaml; default: the built-in config)");
    AddThreadsOption(sub, common);
    sub->callback([opt, &common] { RunSweep(*opt, common); });
}

namespace {

void RunSweep(const SweepOptions& opt, const CommonOptions& common) {
    const auto start = std::chrono::steady_clock::now();
    std::vector<Axis> axes;
    for (const std::string& s : opt.set) {
        axes.push_back(ParseAxis(s));
        for (std::size_t i = 0; i + 1 < axes.size(); ++i) {
            if (axes[i].name == axes.back().name) {
                throw MakeInputError("", "--set", axes.back().name, "parameter given twice");
            }
        }
    }
    const std::vector<int> courses = ParseCourses(opt.courses, "--courses");
    const std::vector<std::string> tests = ParseTests(opt.tests, "--tests");
    BenchSettings settings = CheckBenchSettings(opt.courses_dir, opt.rig, opt.sensor, opt.seed);
    if (!opt.json.empty()) {
        CheckWritableFile(opt.json, "--json");
    }
    // Grid points (row-major over the axes, the first axis varying slowest).
    std::vector<std::vector<double>> points = {{}};
    for (const Axis& axis : axes) {
        std::vector<std::vector<double>> next;
        for (const auto& p : points) {
            for (const double v : axis.values) {
                next.push_back(p);
                next.back().push_back(v);
            }
        }
        points = std::move(next);
        if (points.size() > kMaxPoints) {
            throw MakeInputError("", "--set", "", "more than 10000 grid points");
        }
    }
    // Speeds to simulate and `a` values to map with.
    std::vector<double> speeds = {0.0};  // 0: the rig's own
    std::vector<int> a_values = {3};
    int speed_axis = -1;
    int a_axis = -1;
    for (std::size_t i = 0; i < axes.size(); ++i) {
        if (axes[i].name == "speed") {
            speed_axis = static_cast<int>(i);
            speeds = axes[i].values;
            for (const double v : speeds) {
                if (!(v > 0.0 && v <= rig::TableLimits::kMaxSpeedMS)) {
                    throw MakeInputError("", "--set", "speed=" + FormatNumber(v),
                                         "allowed: > 0 and <= 1 m/s (the table's limit)");
                }
            }
        }
        if (axes[i].name == "a") {
            a_axis = static_cast<int>(i);
            a_values.clear();
            for (const double v : axes[i].values) {
                if (v != std::floor(v) || v < 1 || v > 1000) {
                    throw MakeInputError("", "--set", "a=" + FormatNumber(v),
                                         "allowed: integer 1..1000");
                }
                a_values.push_back(static_cast<int>(v));
            }
        }
    }
    // Validate every point's filter settings and every speed before simulating anything.
    BenchSettings probe = settings;
    std::vector<std::vector<SimSetup>> setups(speeds.size());
    for (std::size_t s = 0; s < speeds.size(); ++s) {
        probe.speed_m_s =
            speeds[s] > 0.0 || speed_axis >= 0 ? std::optional(speeds[s]) : std::nullopt;
        for (const std::string& t : tests) {
            setups[s].push_back(BenchSetup(probe, courses.front(), t));
        }
    }
    for (const auto& p : points) {
        mapper::FilterParams check;
        for (const std::string& o : PointOverrides(opt.fix, axes, p)) {
            check.SetAssignment(o);
        }
        check.Validate();
    }
    const fs::path out(opt.out);
    io::EnsureDirectory(out);
    const int threads = core::ResolveThreads(common.threads);

    std::vector<Course> loaded = LoadCourses(settings, courses, setups[0][0].grid, threads);
    std::vector<core::Trajectory> trajectories(speeds.size() * tests.size());
    core::ParallelFor(trajectories.size(), threads, [&](std::size_t i) {
        trajectories[i] = RigTrajectory(setups[i / tests.size()][i % tests.size()], core::Scene{});
    });

    // One simulated run per speed x course x test; every point is scored on it.
    const std::size_t runs = speeds.size() * courses.size() * tests.size();
    std::vector<std::vector<CasScore>> scores(runs);  // [run][point]; NaN PI when not applicable
    std::vector<std::string> run_configs(runs);
    {
        core::Progress progress("sweep", runs);
        core::ParallelFor(runs, threads, [&](std::size_t r) {
            const std::size_t s = r / (courses.size() * tests.size());
            const std::size_t c = (r / tests.size()) % courses.size();
            const std::size_t t = r % tests.size();
            SimSetup setup = setups[s][t];
            setup.scene_path = loaded[c].path;
            const SimulatedRun sim =
                SimulateBenchRun(setup, loaded[c], trajectories[s * tests.size() + t]);
            std::map<int, MappedBenchRun> by_a;
            for (const int a : a_values) {
                by_a.emplace(a, MapBenchRun(setup, loaded[c], sim, a));
            }
            run_configs[r] = by_a.begin()->second.config_yaml;
            scores[r].assign(points.size(), CasScore{std::nan(""), {}});
            for (std::size_t p = 0; p < points.size(); ++p) {
                if (speed_axis >= 0 &&
                    points[p][static_cast<std::size_t>(speed_axis)] != speeds[s]) {
                    continue;
                }
                const int a = a_axis >= 0
                                  ? static_cast<int>(points[p][static_cast<std::size_t>(a_axis)])
                                  : a_values.front();
                const MappedBenchRun& run = by_a.at(a);
                const mapper::FilterParams params =
                    RunFilterParams(run, PointOverrides(opt.fix, axes, points[p]));
                scores[r][p] = ScoreCas(run, loaded[c], params);
            }
            progress.Advance();
        });
        progress.Finish();
    }
    // Per point: statistics over the runs that apply to it.
    std::vector<Stats> pi(points.size());
    std::vector<std::array<double, 3>> classes(points.size(), {0.0, 0.0, 0.0});
    for (std::size_t p = 0; p < points.size(); ++p) {
        std::vector<double> v;
        std::size_t n = 0;
        for (std::size_t r = 0; r < runs; ++r) {
            const CasScore& sc = scores[r][p];
            if (std::isnan(sc.pi) && sc.classes.all.cells == 0) {
                continue;  // another speed's run
            }
            v.push_back(sc.pi);
            classes[p][0] += sc.classes.all.removed_pct;
            classes[p][1] += sc.classes.all.filled_pct;
            classes[p][2] += sc.classes.all.untouched_pct;
            ++n;
        }
        pi[p] = Summarise(v);
        for (double& c : classes[p]) {
            c = n > 0 ? c / static_cast<double>(n) : std::nan("");
        }
    }
    io::EnsureDirectory(out / "runs");
    for (std::size_t r = 0; r < runs; ++r) {
        const std::size_t s = r / (courses.size() * tests.size());
        const std::size_t c = (r / tests.size()) % courses.size();
        std::string name = RunName(courses[c], tests[r % tests.size()]);
        if (speed_axis >= 0) {
            name += "_speed" + FormatNumber(speeds[s]);
        }
        io::WriteTextAtomically(out / "runs" / (name + ".yaml"), run_configs[r]);
    }
    // JSON.
    std::string j = "{\"parameters\": [";
    for (std::size_t i = 0; i < axes.size(); ++i) {
        j += (i ? ", " : "") + JsonString(axes[i].name);
    }
    j += "], \"fixed\": [";
    for (std::size_t i = 0; i < opt.fix.size(); ++i) {
        j += (i ? ", " : "") + JsonString(opt.fix[i]);
    }
    j += "], \"courses\": [";
    for (std::size_t i = 0; i < courses.size(); ++i) {
        j += (i ? ", " : "") + std::to_string(courses[i]);
    }
    j += "], \"tests\": [";
    for (std::size_t i = 0; i < tests.size(); ++i) {
        j += (i ? ", " : "") + JsonString(tests[i]);
    }
    j += "], \"seed\": " + std::to_string(opt.seed) + ",\n \"points\": [";
    std::size_t best = 0;
    for (std::size_t p = 0; p < points.size(); ++p) {
        j += p ? ",\n  " : "\n  ";
        j += "{\"params\": {";
        for (std::size_t i = 0; i < axes.size(); ++i) {
            j += (i ? ", " : "") + JsonString(axes[i].name) + ": " + JsonNumber(points[p][i]);
        }
        j += "}, \"pi_mean\": " + JsonNumber(pi[p].mean) +
             ", \"pi_std\": " + JsonNumber(pi[p].std) + ", \"pi_min\": " + JsonNumber(pi[p].min) +
             ", \"pi_max\": " + JsonNumber(pi[p].max) +
             ", \"runs\": " + std::to_string(pi[p].runs) +
             ", \"cas_classes_pct_mean\": {\"mixed\": " + JsonNumber(classes[p][0]) +
             ", \"missing\": " + JsonNumber(classes[p][1]) +
             ", \"untouched\": " + JsonNumber(classes[p][2]) + "}}";
        if (std::isfinite(pi[p].mean) &&
            (!std::isfinite(pi[best].mean) || pi[p].mean < pi[best].mean)) {
            best = p;
        }
    }
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    j += "\n], \"best_point\": " + std::to_string(best) +
         ", \"elapsed_s\": " + JsonNumber(elapsed) + ", \"threads\": " + std::to_string(threads) +
         "}\n";
    io::WriteTextAtomically(out / "sweep.json", j);
    if (!opt.json.empty()) {
        io::WriteTextAtomically(opt.json, j);
    }
    if (axes.size() == 2) {
        HeatMap h;
        h.title = "CAS mean PI (Eq. 11) over " + std::to_string(courses.size()) + " course(s) x " +
                  std::to_string(tests.size()) + " test(s); lower is better";
        h.x_name = axes[0].name;
        h.y_name = axes[1].name;
        h.x_values = axes[0].values;
        h.y_values = axes[1].values;
        const std::size_t nx = h.x_values.size();
        const std::size_t ny = h.y_values.size();
        h.values.assign(nx * ny, std::nan(""));
        for (std::size_t ix = 0; ix < nx; ++ix) {
            for (std::size_t iy = 0; iy < ny; ++iy) {
                h.values[iy * nx + ix] = pi[ix * ny + iy].mean;
            }
        }
        WriteHeatMap(out / "heatmap.png", h);
    }
    // Terminal table.
    for (const Axis& a : axes) {
        std::printf("%12s", a.name.c_str());
    }
    std::printf("     pi_mean   pi_std   pi_min   pi_max  runs\n");
    for (std::size_t p = 0; p < points.size(); ++p) {
        for (std::size_t i = 0; i < axes.size(); ++i) {
            std::printf("%12s", FormatNumber(points[p][i]).c_str());
        }
        std::printf("    %8.4f %8.4f %8.4f %8.4f %5zu%s\n", pi[p].mean, pi[p].std, pi[p].min,
                    pi[p].max, pi[p].runs, p == best ? "  <- best" : "");
    }
    std::printf("%zu point(s) x %zu run(s) in %.1f s on %d threads -> %s\n", points.size(), runs,
                elapsed, threads, out.string().c_str());
}

}  // namespace
}  // namespace casmap::app
