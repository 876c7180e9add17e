#include "casmap/pipeline/bench_runner.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>
#include <variant>

#include "casmap/core/input_error.hpp"
#include "casmap/core/parallel.hpp"
#include "casmap/core/text.hpp"
#include "casmap/io/rig_config.hpp"
#include "casmap/io/scene_file.hpp"
#include "casmap/io/sensor_config.hpp"
#include "casmap/mapper/filters.hpp"
#include "casmap/mapper/metrics.hpp"
#include "casmap/pipeline/data_dir.hpp"
#include "casmap/sensor_models/lms200_model.hpp"
#include "casmap/sim/ground_truth.hpp"

namespace casmap::pipeline {
namespace {
namespace fs = std::filesystem;

bool ParseInt(const std::string& s, int& v) {
    const std::optional<int> parsed = core::ParseWholeInt(s);
    v = parsed.value_or(0);
    return parsed.has_value();
}

}  // namespace

std::vector<int> ParseCourses(const std::string& text, const std::string& field) {
    const std::string rule =
        "allowed: courses 1..16 as N, N-M or a comma list, e.g. 1-16 or 1,4,7-9";
    std::set<int> out;
    for (const std::string& part : core::SplitList(text)) {
        const std::size_t dash = part.find('-');
        int lo = 0;
        int hi = 0;
        const bool ok = dash == std::string::npos ? ParseInt(part, lo) && ((hi = lo), true)
                                                  : ParseInt(part.substr(0, dash), lo) &&
                                                        ParseInt(part.substr(dash + 1), hi);
        if (!ok || lo < 1 || hi > 16 || lo > hi) {
            throw MakeInputError("", field, text,
                                 rule + (ok && lo > hi ? " (inverted range)" : ""));
        }
        for (int c = lo; c <= hi; ++c) {
            out.insert(c);
        }
    }
    if (out.empty()) {
        throw MakeInputError("", field, text, rule);
    }
    return {out.begin(), out.end()};
}

std::vector<std::string> ParseTests(const std::string& text, const std::string& field) {
    static const std::vector<std::string> kAll = {"T", "TR", "TP", "TRP"};
    std::set<std::string> given;
    for (const std::string& part : core::SplitList(text)) {
        if (std::find(kAll.begin(), kAll.end(), part) == kAll.end()) {
            throw MakeInputError("", field, part, "allowed: T, TR, TP, TRP (comma separated)");
        }
        given.insert(part);
    }
    if (given.empty()) {
        throw MakeInputError("", field, text, "allowed: T, TR, TP, TRP (comma separated)");
    }
    std::vector<std::string> out;
    for (const std::string& t : kAll) {
        if (given.count(t) != 0) {
            out.push_back(t);
        }
    }
    return out;
}

void CheckCoursesAndTests(const std::vector<int>& courses, const std::vector<std::string>& tests) {
    std::set<int> seen_courses;
    for (const int c : courses) {
        if (c < 1 || c > 16 || !seen_courses.insert(c).second) {
            throw MakeInputError("", "courses", std::to_string(c),
                                 "allowed: courses 1..16, each at most once");
        }
    }
    if (courses.empty()) {
        throw MakeInputError("", "courses", "", "at least one course");
    }
    std::set<std::string> seen_tests;
    for (const std::string& t : tests) {
        const std::vector<std::string> all = {"T", "TR", "TP", "TRP"};
        if (std::find(all.begin(), all.end(), t) == all.end() || !seen_tests.insert(t).second) {
            throw MakeInputError("", "tests", t, "allowed: T, TR, TP, TRP, each at most once");
        }
    }
    if (tests.empty()) {
        throw MakeInputError("", "tests", "", "at least one of T, TR, TP, TRP");
    }
}

std::vector<std::string> SortedTests(const std::vector<std::string>& tests) {
    std::vector<std::string> out;
    for (const std::string t : {"T", "TR", "TP", "TRP"}) {
        if (std::find(tests.begin(), tests.end(), t) != tests.end()) {
            out.push_back(t);
        }
    }
    return out;
}

std::string FindCoursesDir(const std::string& dir) {
    if (!dir.empty()) {
        if (!fs::is_regular_file(fs::path(dir) / "course01.yaml")) {
            throw MakeInputError("", "courses_dir", dir,
                                 "must be a directory holding course01.yaml .. course16.yaml");
        }
        return dir;
    }
    return CoursesDir().string();
}

std::string CoursePath(const std::string& dir, int course) {
    char name[32];
    std::snprintf(name, sizeof(name), "course%02d.yaml", course);
    return (fs::path(dir) / name).string();
}

std::string RunName(int course, const std::string& test) {
    char name[32];
    std::snprintf(name, sizeof(name), "course%02d_%s", course, test.c_str());
    return name;
}

SimSetup BenchSetup(const BenchSettings& settings, int course, const std::string& test) {
    SimFlags flags;
    flags.scene_path = CoursePath(settings.courses_dir, course);
    flags.motion = test;
    flags.seed = settings.seed;
    flags.rig_path = settings.rig_path;
    flags.sensor_path = settings.sensor_path;
    flags.speed_m_s = settings.speed_m_s;
    return ResolveSimSetup(flags);
}

std::vector<Course> LoadCourses(const BenchSettings& settings,
                                const std::vector<int>& courses,
                                const core::GridGeometry& grid,
                                int threads) {
    std::vector<Course> out(courses.size());
    core::ParallelFor(courses.size(), threads, [&](std::size_t i) {
        Course& c = out[i];
        c.number = courses[i];
        c.path = CoursePath(settings.courses_dir, c.number);
        c.scene = io::LoadScene(c.path);
        c.world = std::make_unique<sim::World>(c.scene);
        c.truth = sim::GroundTruthElevation(c.scene, grid, 1);
    });
    return out;
}

SimulatedRun SimulateBenchRun(const SimSetup& setup,
                              const Course& course,
                              const core::Trajectory& poses) {
    SimulateRunOptions options;
    options.threads = 1;
    options.truth = false;
    return SimulateRun(setup, course.scene, *course.world, poses, options);
}

MappedBenchRun MapBenchRun(const SimSetup& setup,
                           const Course& course,
                           const SimulatedRun& sim,
                           int a,
                           mapper::Unknown unknown) {
    MappedBenchRun run;
    run.test = setup.motion_name;
    run.course = course.number;
    run.setup = setup;
    run.scans = sim.run.scans.size();
    MapSettings settings;
    settings.a = a;
    settings.unknown = unknown;
    run.mapped = MapScans(sim.run.scans, sim.run.poses, setup.grid, settings);
    run.config_yaml = sim.run.config_yaml;
    return run;
}

MappedBenchRun SimulateAndMap(const SimSetup& setup,
                              const Course& course,
                              const core::Trajectory& poses,
                              int a) {
    return MapBenchRun(setup, course, SimulateBenchRun(setup, course, poses), a);
}

mapper::FilterParams SetupFilterParams(const SimSetup& setup,
                                       int a,
                                       mapper::Unknown unknown,
                                       const std::vector<std::string>& overrides) {
    mapper::FilterParams p;
    p.cas.cell_m = setup.grid.cell_m;
    p.cas.speed_m_s = setup.vehicle ? setup.vehicle_config.speed_m_s : setup.table.speed_m_s;
    p.cas.scan_period_s = sensor_models::Lms200Model(setup.lms).ScanPeriodS();
    p.cas.a = a;
    if (unknown != mapper::Unknown::kZero) {
        p.Set("unknown", mapper::ToString(unknown));
    }
    for (const std::string& o : overrides) {
        p.SetAssignment(o);
    }
    p.Validate();
    return p;
}

mapper::FilterParams RunFilterParams(const MappedBenchRun& run,
                                     const std::vector<std::string>& overrides) {
    return SetupFilterParams(run.setup, run.mapped.config.a, run.mapped.settings.unknown,
                             overrides);
}

Course LoadSceneCourse(const std::string& path, const core::GridGeometry& grid) {
    Course c;
    c.path = path;
    c.scene = io::LoadScene(path);
    c.world = std::make_unique<sim::World>(c.scene);
    c.truth = sim::GroundTruthElevation(c.scene, grid, 1);
    return c;
}

BenchSettings ResolveBenchSettings(const std::string& courses_dir,
                                   const std::string& rig_path,
                                   const std::string& sensor_path,
                                   std::uint64_t seed) {
    BenchSettings settings;
    settings.courses_dir = FindCoursesDir(courses_dir);
    settings.rig_path = rig_path;
    settings.sensor_path = sensor_path;
    if (!rig_path.empty()) {
        (void)io::LoadRigConfig(rig_path);  // a bad file fails before any work
    }
    if (!sensor_path.empty()) {
        (void)io::LoadLms200Config(sensor_path);
    }
    settings.seed = seed;
    return settings;
}

}  // namespace casmap::pipeline
