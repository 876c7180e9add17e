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

/// RMSE against truth over the cells CAS filled inside `region` (NaN if none).
double FillError(const core::MapF& map,
                 const core::MapF& truth,
                 const mapper::ClassMap& cas_classes,
                 const mapper::Region& region) {
    double sum = 0.0;
    std::int64_t n = 0;
    for (int r = region.row0; r < region.row0 + region.rows; ++r) {
        for (int c = region.col0; c < region.col0 + region.cols; ++c) {
            if (cas_classes.at(r, c) == static_cast<std::uint8_t>(mapper::PixelClass::kFilled)) {
                const double d = static_cast<double>(map.at(r, c)) - truth.at(r, c);
                sum += d * d;
                ++n;
            }
        }
    }
    return n > 0 ? std::sqrt(sum / static_cast<double>(n)) : std::nan("");
}

/// Poles of the scene (objects named pole<N>) with the cell holding their axis.
struct Pole {
    std::string name;
    int row = 0;
    int col = 0;
    double height_m = 0.0;
};

std::vector<Pole> Poles(const core::Scene& scene, const core::GridGeometry& grid) {
    std::vector<Pole> poles;
    for (const core::SceneObject& o : scene.objects) {
        const auto* cyl = std::get_if<core::CylinderShape>(&o.shape);
        if (cyl == nullptr || o.name.rfind("pole", 0) != 0) {
            continue;
        }
        const Eigen::Vector3d& p = o.world_T_object.translation;
        if (const std::optional<core::Cell> cell = grid.CellOf(p.x(), p.y())) {
            poles.push_back({o.name, cell->row, cell->col, p.z() + 0.5 * cyl->height_m});
        }
    }
    std::sort(poles.begin(), poles.end(),
              [](const Pole& a, const Pole& b) { return a.name < b.name; });
    return poles;
}

/// A map keeps a pole when it reaches half the pole's height within one cell of it.
bool Keeps(const core::MapF& map, const Pole& pole) {
    for (int r = std::max(0, pole.row - 1); r <= std::min(map.rows - 1, pole.row + 1); ++r) {
        for (int c = std::max(0, pole.col - 1); c <= std::min(map.cols - 1, pole.col + 1); ++c) {
            if (map.at(r, c) >= 0.5 * pole.height_m) {
                return true;
            }
        }
    }
    return false;
}

std::vector<std::string> KeptPoles(const core::MapF& map, const std::vector<Pole>& poles) {
    std::vector<std::string> kept;
    for (const Pole& p : poles) {
        if (Keeps(map, p)) {
            kept.push_back(p.name);
        }
    }
    return kept;
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
                           int a) {
    MappedBenchRun run;
    run.test = setup.motion_name;
    run.course = course.number;
    run.setup = setup;
    run.scans = sim.run.scans.size();
    MapSettings settings;
    settings.a = a;
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

mapper::FilterParams RunFilterParams(const MappedBenchRun& run,
                                     const std::vector<std::string>& overrides) {
    mapper::FilterParams p;
    p.cas.cell_m = run.setup.grid.cell_m;
    p.cas.speed_m_s = run.setup.table.speed_m_s;
    p.cas.scan_period_s = sensor_models::Lms200Model(run.setup.lms).ScanPeriodS();
    p.cas.a = run.mapped.config.a;
    for (const std::string& o : overrides) {
        p.SetAssignment(o);
    }
    p.Validate();
    return p;
}

BenchRun ScoreRun(const MappedBenchRun& run,
                  const Course& course,
                  const mapper::FilterParams& params,
                  SheetMaps* sheet) {
    const core::MapF& raw = run.mapped.elevation;
    const core::MapF& c = run.mapped.certainty;
    const mapper::Region region = mapper::PaperRegion(raw.rows, raw.cols);
    BenchRun out;
    out.course = run.course;
    out.test = run.test;
    out.seed = run.setup.seed;
    out.scans = static_cast<std::int64_t>(run.scans);
    const mapper::FilterResult cas = mapper::RunFilter(mapper::FilterMethod::kCas, raw, c, params);
    out.cas_classes = mapper::ClassPercentages(cas.classes, c);
    const std::vector<Pole> poles = Poles(course.scene, run.setup.grid);
    for (const Pole& p : poles) {
        out.poles.push_back(p.name);
    }
    out.poles_kept["raw"] = KeptPoles(raw, poles);
    for (const mapper::FilterMethod m : mapper::AllFilterMethods()) {
        const std::string name(mapper::ToString(m));
        const mapper::FilterResult result =
            m == mapper::FilterMethod::kCas ? cas : mapper::RunFilter(m, raw, c, params);
        const mapper::FilterMetrics metrics =
            mapper::EvaluateFilter(result, raw, course.truth, region);
        out.filters[name] =
            FilterScore{metrics.pi, metrics.rmse_m, metrics.spikes,
                        FillError(result.elevation, course.truth, cas.classes, region)};
        out.poles_kept[name] = KeptPoles(result.elevation, poles);
        out.raw_rmse_m = metrics.raw_rmse_m;
        out.raw_spikes = metrics.raw_spikes;
        if (sheet != nullptr) {
            sheet->filtered[name] = result.elevation;
        }
    }
    if (sheet != nullptr) {
        sheet->raw = raw;
        sheet->certainty = c;
        sheet->truth = course.truth;
        sheet->cas_classes = cas.classes;
    }
    return out;
}

CasScore ScoreCas(const MappedBenchRun& run,
                  const Course& course,
                  const mapper::FilterParams& params,
                  mapper::FilterMethod method) {
    const core::MapF& raw = run.mapped.elevation;
    const mapper::FilterResult cas = mapper::RunFilter(method, raw, run.mapped.certainty, params);
    const mapper::Region region = mapper::PaperRegion(raw.rows, raw.cols);
    const std::vector<Pole> poles = Poles(course.scene, run.setup.grid);
    CasScore score;
    score.pi = mapper::PerformanceIndex(cas.elevation, raw, course.truth, region);
    score.classes = mapper::ClassPercentages(cas.classes, run.mapped.certainty);
    score.spikes = mapper::CountSpikes(cas.elevation, course.truth, region);
    score.poles = poles.size();
    score.poles_kept = KeptPoles(cas.elevation, poles).size();
    return score;
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

void CheckWritableFile(const std::string& path, const std::string& field) {
    const std::filesystem::path p(path);
    const std::filesystem::path dir =
        p.has_parent_path() ? p.parent_path() : std::filesystem::path(".");
    if (p.filename().empty() || !std::filesystem::is_directory(dir)) {
        throw MakeInputError(path, field, path, "directory " + dir.string() + " does not exist");
    }
}

}  // namespace casmap::pipeline
