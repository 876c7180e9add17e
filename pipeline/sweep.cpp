#include "casmap/pipeline/sweep.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>

#include "casmap/core/input_error.hpp"
#include "casmap/core/parallel.hpp"
#include "casmap/io/atomic_file.hpp"
#include "casmap/pipeline/bench_runner.hpp"

namespace casmap::pipeline {
namespace {
namespace fs = std::filesystem;

constexpr std::size_t kMaxPoints = 10000;

double ParseNumber(const std::string& text,
                   const std::string& assignment,
                   const std::string& field) {
    std::size_t used = 0;
    double v = 0.0;
    try {
        v = std::stod(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used != text.size() || text.empty() || !std::isfinite(v)) {
        throw MakeInputError("", field, assignment, "FROM, TO and STEP must be numbers");
    }
    return v;
}

/// Grid points, row-major over the axes (the first axis varying slowest).
std::vector<std::vector<double>> GridPoints(const std::vector<SweepAxis>& axes) {
    std::vector<std::vector<double>> points = {{}};
    for (const SweepAxis& axis : axes) {
        std::vector<std::vector<double>> next;
        for (const auto& p : points) {
            for (const double v : axis.values) {
                next.push_back(p);
                next.back().push_back(v);
            }
        }
        points = std::move(next);
        if (points.size() > kMaxPoints) {
            throw MakeInputError("", "axes", "", "more than 10000 grid points");
        }
    }
    return points;
}

/// The filter overrides of one grid point (NAME=VALUE for FilterParams::Set).
std::vector<std::string> PointOverrides(const SweepOptions& opt, const std::vector<double>& point) {
    std::vector<std::string> out = opt.fixed;
    for (std::size_t i = 0; i < opt.axes.size(); ++i) {
        if (opt.axes[i].name == "speed") {
            continue;  // a rig setting; CAS's v follows the run (RunFilterParams)
        }
        out.push_back(opt.axes[i].name + "=" + FormatNumber(point[i]));
        if (opt.axes[i].name == "E") {
            out.push_back("e_term=on");  // sweeping E means using Eq. 10's E term
        }
    }
    return out;
}

int AxisIndex(const SweepOptions& opt, const std::string& name) {
    for (std::size_t i = 0; i < opt.axes.size(); ++i) {
        if (opt.axes[i].name == name) {
            return static_cast<int>(i);
        }
    }
    return -1;
}

/// Speeds to simulate (0: the rig's own) and `a` values to map with.
std::vector<double> Speeds(const SweepOptions& opt) {
    const int i = AxisIndex(opt, "speed");
    return i >= 0 ? opt.axes[static_cast<std::size_t>(i)].values : std::vector<double>{0.0};
}

std::vector<int> AValues(const SweepOptions& opt) {
    const int i = AxisIndex(opt, "a");
    std::vector<int> out;
    for (const double v :
         i >= 0 ? opt.axes[static_cast<std::size_t>(i)].values : std::vector<double>{3.0}) {
        out.push_back(static_cast<int>(v));
    }
    return out;
}

/// Setups per speed x test (test-major within a speed).
std::vector<std::vector<SimSetup>> Setups(const SweepOptions& opt,
                                          const BenchSettings& settings,
                                          const std::vector<std::string>& tests) {
    const bool swept = AxisIndex(opt, "speed") >= 0;
    std::vector<std::vector<SimSetup>> setups;
    BenchSettings probe = settings;
    for (const double v : Speeds(opt)) {
        probe.speed_m_s = swept ? std::optional(v) : std::nullopt;
        setups.emplace_back();
        for (const std::string& t : tests) {
            setups.back().push_back(BenchSetup(probe, opt.courses.front(), t));
        }
    }
    return setups;
}

}  // namespace

const std::vector<std::string>& SweepableParameters() {
    static const std::vector<std::string> names = {"A", "G", "B", "h_sum_min",
                                                   "a", "E", "k", "speed"};
    return names;
}

SweepAxis ParseSweepAxis(const std::string& assignment, const std::string& field) {
    const std::size_t eq = assignment.find('=');
    const std::string rule = "expected NAME=FROM:TO:STEP with FROM <= TO and STEP > 0";
    if (eq == std::string::npos) {
        throw MakeInputError("", field, assignment, rule);
    }
    SweepAxis axis;
    axis.name = assignment.substr(0, eq);
    const std::vector<std::string>& names = SweepableParameters();
    if (std::find(names.begin(), names.end(), axis.name) == names.end()) {
        throw MakeInputError("", field, axis.name,
                             "unknown parameter; allowed: A, G, B, h_sum_min, a, E, k, speed");
    }
    const std::string range = assignment.substr(eq + 1);
    const std::size_t c1 = range.find(':');
    const std::size_t c2 = c1 == std::string::npos ? c1 : range.find(':', c1 + 1);
    if (c2 == std::string::npos || range.find(':', c2 + 1) != std::string::npos) {
        throw MakeInputError("", field, assignment, rule);
    }
    const double from = ParseNumber(range.substr(0, c1), assignment, field);
    const double to = ParseNumber(range.substr(c1 + 1, c2 - c1 - 1), assignment, field);
    const double step = ParseNumber(range.substr(c2 + 1), assignment, field);
    if (!(step > 0.0)) {
        throw MakeInputError("", field, assignment, "STEP must be > 0 (" + rule + ")");
    }
    if (from > to) {
        throw MakeInputError("", field, assignment, "inverted range: FROM > TO (" + rule + ")");
    }
    const double count = std::floor((to - from) / step * (1.0 + 1e-12) + 1e-9) + 1.0;
    if (count > static_cast<double>(kMaxPoints)) {
        throw MakeInputError("", field, assignment, "more than 10000 values");
    }
    for (int i = 0; i < static_cast<int>(count); ++i) {
        axis.values.push_back(from + i * step);
    }
    return axis;
}

void SweepOptions::Validate() const {
    const std::vector<std::string>& names = SweepableParameters();
    for (std::size_t i = 0; i < axes.size(); ++i) {
        const SweepAxis& axis = axes[i];
        if (std::find(names.begin(), names.end(), axis.name) == names.end()) {
            throw MakeInputError("", "axes", axis.name,
                                 "unknown parameter; allowed: A, G, B, h_sum_min, a, E, k, speed");
        }
        if (axis.values.empty()) {
            throw MakeInputError("", "axes", axis.name, "at least one value");
        }
        for (std::size_t j = 0; j < i; ++j) {
            if (axes[j].name == axis.name) {
                throw MakeInputError("", "axes", axis.name, "parameter given twice");
            }
        }
        for (const double v : axis.values) {
            if (axis.name == "speed" && !(v > 0.0 && v <= rig::TableLimits::kMaxSpeedMS)) {
                throw MakeInputError("", "axes", "speed=" + FormatNumber(v),
                                     "allowed: > 0 and <= 1 m/s (the table's limit)");
            }
            if (axis.name == "a" && (v != std::floor(v) || v < 1 || v > 1000)) {
                throw MakeInputError("", "axes", "a=" + FormatNumber(v),
                                     "allowed: integer 1..1000");
            }
        }
    }
    CheckCoursesAndTests(courses, tests);
    const BenchSettings settings = ResolveBenchSettings(courses_dir, rig_path, sensor_path, seed);
    (void)Setups(*this, settings, SortedTests(tests));
    for (const auto& p : GridPoints(axes)) {
        mapper::FilterParams check;
        for (const std::string& o : PointOverrides(*this, p)) {
            check.SetAssignment(o);
        }
        check.Validate();
    }
}

SweepStats Summarise(const std::vector<double>& values) {
    SweepStats s;
    std::vector<double> finite;
    for (const double x : values) {
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

SweepResult RunSweep(const SweepOptions& options, const core::ProgressFn& progress) {
    const auto start = std::chrono::steady_clock::now();
    options.Validate();  // every point and speed, before simulating anything
    const BenchSettings settings = ResolveBenchSettings(options.courses_dir, options.rig_path,
                                                        options.sensor_path, options.seed);
    const std::vector<int>& courses = options.courses;
    const std::vector<std::string> tests = SortedTests(options.tests);
    const std::vector<std::vector<double>> points = GridPoints(options.axes);
    const std::vector<double> speeds = Speeds(options);
    const std::vector<int> a_values = AValues(options);
    const int speed_axis = AxisIndex(options, "speed");
    const int a_axis = AxisIndex(options, "a");
    const std::vector<std::vector<SimSetup>> setups = Setups(options, settings, tests);
    const int threads = core::ResolveThreads(options.threads);

    const std::vector<Course> loaded = LoadCourses(settings, courses, setups[0][0].grid, threads);
    std::vector<core::Trajectory> trajectories(speeds.size() * tests.size());
    core::ParallelFor(trajectories.size(), threads, [&](std::size_t i) {
        trajectories[i] = RigTrajectory(setups[i / tests.size()][i % tests.size()], core::Scene{});
    });

    // One simulated run per speed x course x test; every point is scored on it.
    const std::size_t runs = speeds.size() * courses.size() * tests.size();
    std::vector<std::vector<std::optional<CasScore>>> scores(runs);  // [run][point]
    SweepResult result;
    result.run_names.resize(runs);
    result.run_configs.resize(runs);
    core::ProgressCounter counter(progress, runs);
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
        result.run_configs[r] = by_a.begin()->second.config_yaml;
        result.run_names[r] = RunName(courses[c], tests[t]) +
                              (speed_axis >= 0 ? "_speed" + FormatNumber(speeds[s]) : "");
        scores[r].assign(points.size(), std::nullopt);
        for (std::size_t p = 0; p < points.size(); ++p) {
            if (speed_axis >= 0 && points[p][static_cast<std::size_t>(speed_axis)] != speeds[s]) {
                continue;  // another speed's run
            }
            const int a = a_axis >= 0
                              ? static_cast<int>(points[p][static_cast<std::size_t>(a_axis)])
                              : a_values.front();
            const MappedBenchRun& run = by_a.at(a);
            scores[r][p] =
                ScoreCas(run, loaded[c], RunFilterParams(run, PointOverrides(options, points[p])));
        }
        counter.Advance();
    });
    // Per point: statistics over the runs that apply to it.
    result.points.resize(points.size());
    for (std::size_t p = 0; p < points.size(); ++p) {
        SweepPoint& point = result.points[p];
        point.values = points[p];
        std::vector<double> pi;
        double shares[3] = {0.0, 0.0, 0.0};
        double spikes = 0.0;
        for (std::size_t r = 0; r < runs; ++r) {
            if (const std::optional<CasScore>& sc = scores[r][p]) {
                pi.push_back(sc->pi);
                shares[0] += sc->classes.all.removed_pct;
                shares[1] += sc->classes.all.filled_pct;
                shares[2] += sc->classes.all.untouched_pct;
                spikes += static_cast<double>(sc->spikes);
                point.runs_all_poles_kept += sc->poles_kept == sc->poles ? 1 : 0;
            }
        }
        point.pi = Summarise(pi);
        const double n = pi.empty() ? std::nan("") : static_cast<double>(pi.size());
        point.mixed_pct = shares[0] / n;
        point.missing_pct = shares[1] / n;
        point.untouched_pct = shares[2] / n;
        point.spikes_mean = spikes / n;
        const SweepStats& best = result.points[result.best].pi;
        if (std::isfinite(point.pi.mean) &&
            (!std::isfinite(best.mean) || point.pi.mean < best.mean)) {
            result.best = p;
        }
    }
    result.options = options;
    result.threads = threads;
    result.elapsed_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
}

}  // namespace casmap::pipeline
