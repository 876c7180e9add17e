#include "casmap/pipeline/sweep_train.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "casmap/core/parallel.hpp"
#include "casmap/pipeline/sweep_detail.hpp"
#include "casmap/pipeline/sweep_payload.hpp"

namespace casmap::pipeline::detail {
namespace {

/// The setup and true poses of one run (seed, speed, test); scene from `course`.
SimSetup RunSetup(const Context& cx,
                  const SweepOptions& opt,
                  std::uint64_t seed,
                  double speed,
                  const std::string& test,
                  const Course& course) {
    BenchSettings s = cx.settings;
    s.seed = seed;
    s.speed_m_s = detail::AxisIndex(opt, "speed") >= 0 ? std::optional(speed) : std::nullopt;
    SimSetup setup = BenchSetup(s, course.number, test);
    setup.scene_path = course.path;
    return setup;
}

int PointA(const SweepOptions& opt, const Point& p) {
    const int i = detail::AxisIndex(opt, "a");
    return i >= 0 ? static_cast<int>(p[static_cast<std::size_t>(i)]) : 3;
}

bool Applies(const SweepOptions& opt, const Point& p, const TrainRun& run) {
    const int i = detail::AxisIndex(opt, "speed");
    return i < 0 || p[static_cast<std::size_t>(i)] == run.speed;
}

/// The swept filter's score on one mapped run: the filter alone on the paper's map for cas,
/// cas_trail and cas_terrain; any other pipeline through ScorePipelines (it may map `sim`'s
/// scans again: a pre-filter or the Kalman mapper), without Table II shares.
CasScore ScoreSwept(const Context& cx,
                    const MappedBenchRun& run,
                    const SimulatedRun* sim,
                    const Course& course,
                    const mapper::FilterParams& params,
                    StageMaps* stage_maps = nullptr) {
    if (cx.method) {
        return ScoreCas(run, course, params, *cx.method);
    }
    const BenchRun b =
        ScorePipelines(run, sim, course, params, {cx.opt.filter}, nullptr, {}, stage_maps);
    CasScore s;
    s.pi = b.filters.at(cx.opt.filter).pi;
    s.spikes = b.filters.at(cx.opt.filter).spikes;
    s.poles = b.poles.size();
    const auto kept = b.poles_kept.find(cx.opt.filter);
    s.poles_kept = kept != b.poles_kept.end() ? kept->second.size() : 0;
    s.classes.all.removed_pct = std::nan("");
    s.classes.all.filled_pct = std::nan("");
    s.classes.all.untouched_pct = std::nan("");
    return s;
}

/// Accumulates one run's score into a point.
void Add(SweepPoint& pt, const CasScore& s, std::vector<double>& pis) {
    pis.push_back(s.pi);
    pt.mixed_pct += s.classes.all.removed_pct;
    pt.missing_pct += s.classes.all.filled_pct;
    pt.untouched_pct += s.classes.all.untouched_pct;
    pt.spikes_total += s.spikes;
    pt.runs_scored += 1;
    pt.runs_all_poles_kept += s.poles_kept == s.poles ? 1 : 0;
    pt.poles += s.poles;
    pt.poles_kept += s.poles_kept;
}

}  // namespace

std::vector<TrainRun> TrainingRuns(const Context& cx, const SweepOptions& opt) {
    std::vector<TrainRun> runs;
    const bool speed_axis = detail::AxisIndex(opt, "speed") >= 0;
    for (const std::uint64_t seed : cx.seeds) {
        for (const double v : detail::Speeds(opt)) {
            for (const int c : opt.courses) {
                for (const std::string& t : cx.tests) {
                    std::string name = RunName(c, t);
                    name += cx.seeds.size() > 1 ? "_seed" + std::to_string(seed) : "";
                    name += speed_axis ? "_speed" + FormatNumber(v) : "";
                    runs.push_back({seed, v, c, t, std::move(name)});
                }
            }
        }
    }
    return runs;
}

/// One training round: scores `points` on every run they apply to.
std::map<Point, SweepPoint> TrainRound(const Context& cx,
                                       const SweepOptions& opt,
                                       const std::vector<Point>& points,
                                       const core::ProgressFn& progress,
                                       std::map<std::string, std::string>& configs) {
    const std::vector<TrainRun> runs = TrainingRuns(cx, opt);
    std::vector<std::size_t> items;
    for (std::size_t r = 0; r < runs.size(); ++r) {
        if (std::any_of(points.begin(), points.end(),
                        [&](const Point& p) { return Applies(opt, p, runs[r]); })) {
            items.push_back(r);
        }
    }
    // Points that share `a` and the mapping stages' values share a map: scoring them one group
    // after the other maps each stage setting once per run and round.
    std::vector<int> map_axes;
    for (std::size_t i = 0; i < opt.axes.size(); ++i) {
        if (opt.axes[i].name == "a" || IsStageParameter(opt.axes[i].name)) {
            map_axes.push_back(static_cast<int>(i));
        }
    }
    std::vector<std::size_t> order(points.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) {
        for (const int i : map_axes) {
            const auto k = static_cast<std::size_t>(i);
            if (points[x][k] != points[y][k]) {
                return points[x][k] < points[y][k];
            }
        }
        return false;
    });
    const bool cache = opt.cache_runs;
    const auto work = [&](std::size_t r) -> std::string {
        try {
            const TrainRun& run = runs[r];
            const Course& course = cx.CourseOf(run.course);
            const SimSetup setup = RunSetup(cx, opt, run.seed, run.speed, run.test, course);
            // Simulated only when a map is not cached (or the pipeline maps the scans again).
            std::shared_ptr<const SimulatedRun> sim =
                cache && cx.maps_scans ? cx.cache.FindSim(run.name) : nullptr;
            const auto simulated = [&]() -> const SimulatedRun& {
                if (!sim) {
                    auto made = std::make_shared<SimulatedRun>(
                        SimulateBenchRun(setup, course, RigTrajectory(setup, core::Scene{})));
                    cx.simulated_runs.fetch_add(1);
                    if (cache && cx.maps_scans) {
                        made->run.truth = {};  // labels: never read by the mappers
                        made->true_poses = {};
                        cx.cache.StoreSim(run.name, made);
                    }
                    sim = std::move(made);
                }
                return *sim;
            };
            std::map<int, std::shared_ptr<const MappedBenchRun>> by_a;
            const auto mapped_for = [&](int a) -> const MappedBenchRun& {
                if (by_a.count(a) == 0 && cache) {
                    by_a[a] = cx.cache.Find(run.name, a);
                }
                if (!by_a[a]) {
                    cx.paper_maps.fetch_add(1);
                    by_a[a] = std::make_shared<const MappedBenchRun>(
                        MapBenchRun(setup, course, simulated(), a));
                    if (cache) {
                        cx.cache.Store(run.name, a, by_a[a]);
                    }
                }
                return *by_a[a];
            };
            StageMaps* stages = cache && cx.maps_scans ? &cx.cache.Stages(run.name) : nullptr;
            std::vector<std::optional<CasScore>> scores(points.size());
            int min_a = std::numeric_limits<int>::max();
            for (const std::size_t k : order) {
                const Point& p = points[k];
                if (!Applies(opt, p, run)) {
                    continue;
                }
                const int a = PointA(opt, p);
                min_a = std::min(min_a, a);
                const MappedBenchRun& mapped = mapped_for(a);
                const SimulatedRun* scans = cx.maps_scans ? &simulated() : nullptr;
                scores[k] =
                    ScoreSwept(cx, mapped, scans, course,
                               RunFilterParams(mapped, detail::PointOverrides(opt, p)), stages);
            }
            std::string out = "R";
            for (const std::optional<CasScore>& score : scores) {
                out += score ? '1' : '0';
                if (score) {
                    PutScore(out, *score);
                }
            }
            PutStr(out, mapped_for(min_a).config_yaml);  // the smallest a of this round's points
            return out;
        } catch (const std::exception& e) {
            return std::string("E") + e.what();
        }
    };
    core::ProgressCounter counter(cx.session->rank() == 0 ? progress : core::ProgressFn{},
                                  items.size());
    const auto done = [&](std::size_t, const std::string&) { counter.Advance(); };
    std::vector<std::size_t> index(items.size());
    std::iota(index.begin(), index.end(), std::size_t{0});
    const auto payloads = DistributeWork(
        *cx.session, index, cx.threads, [&](std::size_t i) { return work(items[i]); }, done);
    const std::vector<std::string> got = Gather(*cx.session, payloads, items.size());

    std::map<Point, SweepPoint> out;
    std::map<Point, std::vector<double>> pis;
    for (std::size_t i = 0; i < items.size(); ++i) {
        Reader r{got[i], 1};
        for (const Point& p : points) {
            if (got[i].at(r.at++) == '1') {
                Add(out[p], GetScore(r), pis[p]);
            }
        }
        configs.emplace(runs[items[i]].name, r.Str());  // the first round's stays
    }
    for (const Point& p : points) {
        SweepPoint& pt = out[p];
        pt.values = p;
        pt.pi = Summarise(pis[p]);
        const double n = pt.runs_scored ? static_cast<double>(pt.runs_scored) : std::nan("");
        pt.mixed_pct /= n;
        pt.missing_pct /= n;
        pt.untouched_pct /= n;
        pt.spikes_mean = static_cast<double>(pt.spikes_total) / n;
    }
    return out;
}

/// Scores the chosen point and the paper's CAS on every held-out run.
std::vector<HeldOutRun> HeldOut(const Context& cx,
                                const SweepOptions& opt,
                                const Point& best,
                                const core::ProgressFn& progress) {
    std::vector<HeldOutRun> runs;
    for (const std::uint64_t seed : cx.held_seeds) {
        for (const int c : cx.held_courses) {
            for (const std::string& t : cx.tests) {
                HeldOutRun h;
                h.seed = seed;
                h.course = c;
                h.test = t;
                h.name = "seed" + std::to_string(seed) + "_" + RunName(c, t);
                runs.push_back(std::move(h));
            }
        }
    }
    const int speed_axis = detail::AxisIndex(opt, "speed");
    const double speed = speed_axis >= 0 ? best[static_cast<std::size_t>(speed_axis)] : 0.0;
    const auto work = [&](std::size_t k) -> std::string {
        try {
            const Course& course = cx.CourseOf(runs[k].course);
            const SimSetup setup = RunSetup(cx, opt, runs[k].seed, speed, runs[k].test, course);
            const core::Trajectory poses = RigTrajectory(setup, core::Scene{});
            const SimulatedRun sim = SimulateBenchRun(setup, course, poses);
            const int a = PointA(opt, best);
            const MappedBenchRun chosen_run = MapBenchRun(setup, course, sim, a);
            const MappedBenchRun paper_run =
                a == 3 ? chosen_run : MapBenchRun(setup, course, sim, 3);
            std::string out = "R";
            PutScore(out,
                     ScoreSwept(cx, chosen_run, &sim, course,
                                RunFilterParams(chosen_run, detail::PointOverrides(opt, best))));
            PutScore(out, ScoreCas(paper_run, course, RunFilterParams(paper_run, {})));
            return out;
        } catch (const std::exception& e) {
            return std::string("E") + e.what();
        }
    };
    core::ProgressCounter counter(cx.session->rank() == 0 ? progress : core::ProgressFn{},
                                  runs.size());
    std::vector<std::size_t> items(runs.size());
    std::iota(items.begin(), items.end(), std::size_t{0});
    const auto payloads =
        DistributeWork(*cx.session, items, cx.threads, work,
                       [&](std::size_t, const std::string&) { counter.Advance(); });
    const std::vector<std::string> got = Gather(*cx.session, payloads, runs.size());
    for (std::size_t k = 0; k < runs.size(); ++k) {
        Reader r{got[k], 1};
        const CasScore chosen = GetScore(r);
        const CasScore paper = GetScore(r);
        runs[k].chosen = {chosen.pi, chosen.spikes, chosen.poles, chosen.poles_kept};
        runs[k].paper = {paper.pi, paper.spikes, paper.poles, paper.poles_kept};
    }
    return runs;
}

}  // namespace casmap::pipeline::detail
