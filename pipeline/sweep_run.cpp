// RunSweep (sweep.hpp): training rounds over the grid (each a DistributeWork over the simulated
// runs, one payload per run carrying every new point's figures), growth of edge axes, the
// choice of the best point, and the held-out scoring of that point beside the paper's CAS.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <numeric>
#include <optional>
#include <stdexcept>

#include "casmap/core/parallel.hpp"
#include "casmap/pipeline/bench_pipelines.hpp"
#include "casmap/pipeline/distributed.hpp"
#include "casmap/pipeline/sweep.hpp"
#include "casmap/pipeline/sweep_detail.hpp"

namespace casmap::pipeline {
namespace {

using Point = std::vector<double>;

// --- exact bytes (doubles bit for bit) for payloads and the broadcast ---
void PutU64(std::string& out, std::uint64_t v) {
    char b[8];
    std::memcpy(b, &v, 8);
    out.append(b, 8);
}
void PutF64(std::string& out, double v) {
    std::uint64_t u = 0;
    std::memcpy(&u, &v, 8);
    PutU64(out, u);
}
void PutStr(std::string& out, const std::string& s) {
    PutU64(out, s.size());
    out += s;
}
struct Reader {
    const std::string& in;
    std::size_t at = 0;
    std::uint64_t U64() {
        if (at + 8 > in.size()) {
            throw std::runtime_error("sweep payload truncated");
        }
        std::uint64_t v = 0;
        std::memcpy(&v, in.data() + at, 8);
        at += 8;
        return v;
    }
    double F64() {
        const std::uint64_t u = U64();
        double v = 0.0;
        std::memcpy(&v, &u, 8);
        return v;
    }
    std::string Str() {
        const std::size_t n = static_cast<std::size_t>(U64());
        if (at + n > in.size()) {
            throw std::runtime_error("sweep payload truncated");
        }
        std::string s = in.substr(at, n);
        at += n;
        return s;
    }
};

void PutScore(std::string& out, const CasScore& s) {
    PutF64(out, s.pi);
    PutF64(out, s.classes.all.removed_pct);
    PutF64(out, s.classes.all.filled_pct);
    PutF64(out, s.classes.all.untouched_pct);
    PutU64(out, static_cast<std::uint64_t>(s.spikes));
    PutU64(out, s.poles);
    PutU64(out, s.poles_kept);
}
CasScore GetScore(Reader& r) {
    CasScore s;
    s.pi = r.F64();
    s.classes.all.removed_pct = r.F64();
    s.classes.all.filled_pct = r.F64();
    s.classes.all.untouched_pct = r.F64();
    s.spikes = static_cast<std::int64_t>(r.U64());
    s.poles = static_cast<std::size_t>(r.U64());
    s.poles_kept = static_cast<std::size_t>(r.U64());
    return s;
}

/// Rank 0's payloads (item order) on every rank; throws if any item failed ('E' + message).
std::vector<std::string> Gather(const DistributedSession& session,
                                const std::map<std::size_t, std::string>& payloads,
                                std::size_t count) {
    std::string all;
    if (session.rank() == 0) {
        for (const auto& [item, payload] : payloads) {
            PutU64(all, item);
            PutStr(all, payload);
        }
    }
    all = session.Broadcast(std::move(all));
    std::vector<std::string> out(count);
    Reader r{all};
    while (r.at < all.size()) {
        const std::size_t item = static_cast<std::size_t>(r.U64());
        out.at(item) = r.Str();
    }
    for (const std::string& p : out) {
        if (p.empty()) {
            throw std::runtime_error("sweep: a run sent no result");
        }
        if (p.front() == 'E') {
            throw std::runtime_error(p.substr(1));
        }
    }
    return out;
}

/// The training runs of this process, kept across grid points and rounds (growth, descent
/// lines) when SweepOptions::cache_runs: the paper maps per run and `a`; for a named pipeline
/// that maps the scans again (pre-filter, Kalman mapper), the simulated scans and poses (no
/// truth labels) and that run's StageMaps. A run is worked on by one thread at a time; the
/// lock guards the containers only. Results never depend on it.
class RunCache {
public:
    std::shared_ptr<const MappedBenchRun> Find(const std::string& run, int a) {
        const std::lock_guard<std::mutex> lock(mutex_);
        const auto it = maps_.find({run, a});
        return it != maps_.end() ? it->second : nullptr;
    }
    void Store(const std::string& run, int a, std::shared_ptr<const MappedBenchRun> map) {
        const std::lock_guard<std::mutex> lock(mutex_);
        maps_[{run, a}] = std::move(map);
    }
    std::shared_ptr<const SimulatedRun> FindSim(const std::string& run) {
        const std::lock_guard<std::mutex> lock(mutex_);
        const auto it = sims_.find(run);
        return it != sims_.end() ? it->second : nullptr;
    }
    void StoreSim(const std::string& run, std::shared_ptr<const SimulatedRun> sim) {
        const std::lock_guard<std::mutex> lock(mutex_);
        sims_[run] = std::move(sim);
    }
    StageMaps& Stages(const std::string& run) {
        const std::lock_guard<std::mutex> lock(mutex_);
        std::unique_ptr<StageMaps>& s = stages_[run];
        if (!s) {
            s = std::make_unique<StageMaps>(4);
        }
        return *s;
    }

private:
    std::mutex mutex_;
    std::map<std::pair<std::string, int>, std::shared_ptr<const MappedBenchRun>> maps_;
    std::map<std::string, std::shared_ptr<const SimulatedRun>> sims_;
    std::map<std::string, std::unique_ptr<StageMaps>> stages_;
};

/// Everything every run needs: settings, courses (training and held-out), trajectories.
struct Context {
    explicit Context(const SweepOptions& o) : opt(o) {}
    const SweepOptions& opt;
    BenchSettings settings;
    std::vector<std::string> tests;
    std::vector<std::uint64_t> seeds;       // training
    std::vector<std::uint64_t> held_seeds;  // held-out
    std::vector<int> held_courses;
    std::vector<int> all_courses;                // sorted union
    std::vector<Course> loaded;                  // per all_courses
    std::optional<mapper::FilterMethod> method;  // nullopt: opt.filter via ScorePipelines
    bool maps_scans = false;  // opt.filter maps the scans again (a pre-filter, Kalman mapper)
    int threads = 1;
    const DistributedSession* session = nullptr;
    mutable RunCache cache;
    mutable std::atomic<std::size_t> simulated_runs{0};  // training rounds, this process
    mutable std::atomic<std::size_t> paper_maps{0};

    const Course& CourseOf(int number) const {
        const auto it = std::lower_bound(all_courses.begin(), all_courses.end(), number);
        return loaded[static_cast<std::size_t>(it - all_courses.begin())];
    }
};

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

struct TrainRun {
    std::uint64_t seed;
    double speed;
    int course;
    std::string test;
    std::string name;
};

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

/// The chosen point: lowest finite mean PI among points keeping every pole in every run; if
/// none does, the most poles kept, then the lowest mean PI. First in grid order on ties.
void ChooseBest(SweepResult& result) {
    std::optional<std::size_t> best;
    bool any_keep = false;
    for (const SweepPoint& p : result.points) {
        any_keep = any_keep || (p.KeepsEveryPole() && std::isfinite(p.pi.mean));
    }
    for (std::size_t i = 0; i < result.points.size(); ++i) {
        const SweepPoint& p = result.points[i];
        if (!std::isfinite(p.pi.mean) || (any_keep && !p.KeepsEveryPole())) {
            continue;
        }
        if (!best) {
            best = i;
            continue;
        }
        const SweepPoint& b = result.points[*best];
        const bool better = any_keep ? p.pi.mean < b.pi.mean
                                     : (p.poles_kept > b.poles_kept ||
                                        (p.poles_kept == b.poles_kept && p.pi.mean < b.pi.mean));
        best = better ? i : *best;
    }
    result.best = best.value_or(0);
    result.best_keeps_every_pole = any_keep;
    result.best_rule = any_keep ? "lowest mean PI among the points that kept every pole in every "
                                  "training run"
                                : "no point kept every pole in every training run: most poles "
                                  "kept, then lowest mean PI";
}

/// Points not dominated in (mean PI lower, poles kept higher, spikes lower).
std::vector<std::size_t> ParetoFront(const std::vector<SweepPoint>& points) {
    std::vector<std::size_t> front;
    for (std::size_t i = 0; i < points.size(); ++i) {
        const SweepPoint& p = points[i];
        if (!std::isfinite(p.pi.mean)) {
            continue;
        }
        bool dominated = false;
        for (std::size_t j = 0; j < points.size() && !dominated; ++j) {
            const SweepPoint& q = points[j];
            if (j == i || !std::isfinite(q.pi.mean)) {
                continue;
            }
            const bool no_worse = q.pi.mean <= p.pi.mean && q.poles_kept >= p.poles_kept &&
                                  q.spikes_total <= p.spikes_total;
            const bool better = q.pi.mean < p.pi.mean || q.poles_kept > p.poles_kept ||
                                q.spikes_total < p.spikes_total;
            dominated = no_worse && better;
        }
        if (!dominated) {
            front.push_back(i);
        }
    }
    return front;
}

/// Extends every axis (or only `only_axis` when >= 0) whose edge holds the best point, when
/// the value beyond is allowed and the grid stays <= 10000 points; returns the growth records
/// (empty: nothing grew, `opt` unchanged).
std::vector<SweepGrowth> Grow(SweepOptions& opt,
                              const SweepPoint& best,
                              int round,
                              int only_axis = -1) {
    SweepOptions next = opt;
    std::vector<SweepGrowth> grown;
    for (std::size_t i = 0; i < next.axes.size(); ++i) {
        SweepAxis& axis = next.axes[i];
        const std::size_t n = axis.values.size();
        if (n < 2 || (only_axis >= 0 && static_cast<std::size_t>(only_axis) != i)) {
            continue;  // a single value has no step to grow by
        }
        const double v = best.values[i];
        std::optional<double> added;
        if (v == axis.values.front()) {
            const double value = detail::Snap(axis.values[0] - (axis.values[1] - axis.values[0]));
            if (detail::AxisValueAllowed(next, axis.name, value)) {
                axis.values.insert(axis.values.begin(), value);
                added = value;
            }
        } else if (v == axis.values.back()) {
            const double value =
                detail::Snap(axis.values[n - 1] + (axis.values[n - 1] - axis.values[n - 2]));
            if (detail::AxisValueAllowed(next, axis.name, value)) {
                axis.values.push_back(value);
                added = value;
            }
        }
        if (added) {
            grown.push_back({round, axis.name, {*added}, best.values});
        }
    }
    std::size_t total = 1;
    for (const SweepAxis& a : next.axes) {
        total *= a.values.size();
    }
    if (total > 10000 || grown.empty()) {
        return {};
    }
    opt = std::move(next);
    return grown;
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

/// Coordinate descent over the axes' values: start at each axis's middle value; per axis in
/// turn, score the line through the current best point along that axis, move to the best
/// point scored so far (ChooseBest's rule), grow that axis while the best sits on its edge
/// (opt.grow rounds in all); repeat passes until a pass leaves the best point unchanged.
template <typename Evaluate, typename Unscored>
void Descend(SweepOptions& opt,
             SweepResult& result,
             const Evaluate& evaluate,
             const Unscored& unscored) {
    constexpr int kMaxPasses = 20;
    Point current;
    for (const SweepAxis& axis : opt.axes) {
        current.push_back(axis.values[(axis.values.size() - 1) / 2]);
    }
    evaluate(unscored({current}));
    int rounds = 0;
    for (int pass = 1; pass <= kMaxPasses; ++pass) {
        const Point before = result.points[result.best].values;
        for (std::size_t i = 0; i < opt.axes.size(); ++i) {
            for (;;) {
                current = result.points[result.best].values;
                std::vector<Point> line;
                for (const double v : opt.axes[i].values) {
                    line.push_back(current);
                    line.back()[i] = v;
                }
                evaluate(unscored(line));
                if (rounds >= opt.grow) {
                    break;
                }
                const std::vector<SweepGrowth> grown =
                    Grow(opt, result.points[result.best], rounds + 1, static_cast<int>(i));
                if (grown.empty()) {
                    break;
                }
                ++rounds;
                result.growth.insert(result.growth.end(), grown.begin(), grown.end());
                evaluate({});  // re-list the points in the grown grid's order
            }
            result.path.push_back(
                {pass, opt.axes[i].name, result.points[result.best].values, result.points.size()});
        }
        if (result.points[result.best].values == before) {
            break;
        }
    }
}

}  // namespace

SweepResult RunSweep(const SweepOptions& options, const core::ProgressFn& progress) {
    const auto start = std::chrono::steady_clock::now();
    options.Validate();  // every point and speed, before simulating anything
    const DistributedSession local = DistributedSession::Local();
    Context cx(options);
    cx.settings = ResolveBenchSettings(options.courses_dir, options.rig_path, options.sensor_path,
                                       options.seed);
    cx.session = options.session != nullptr ? options.session : &local;
    cx.tests = SortedTests(options.tests);
    cx.seeds = options.TrainSeeds();
    cx.held_seeds = options.test_seeds.empty() ? cx.seeds : options.test_seeds;
    cx.held_courses = options.test_courses.empty() ? options.courses : options.test_courses;
    cx.all_courses = options.courses;
    if (options.HasHeldOut()) {
        cx.all_courses.insert(cx.all_courses.end(), cx.held_courses.begin(), cx.held_courses.end());
    }
    std::sort(cx.all_courses.begin(), cx.all_courses.end());
    cx.all_courses.erase(std::unique(cx.all_courses.begin(), cx.all_courses.end()),
                         cx.all_courses.end());
    cx.method = detail::SweepFilter(options);
    const PipelineSpec& spec = FindPipeline(options.filter, "filter");
    cx.maps_scans =
        !cx.method && (spec.mode != MapperMode::kPaper || spec.prefilter != Prefilter::kNone);
    cx.threads = core::ResolveThreads(options.threads);
    const SimSetup probe = BenchSetup(cx.settings, options.courses.front(), cx.tests.front());
    cx.loaded = LoadCourses(cx.settings, cx.all_courses, probe.grid, cx.threads);

    SweepResult result;
    SweepOptions opt = options;  // axes grow
    std::map<Point, SweepPoint> scored;
    std::map<std::string, std::string> configs;  // per training run name
    const auto evaluate = [&](const std::vector<Point>& fresh) {
        if (!fresh.empty()) {
            for (auto& [p, pt] : TrainRound(cx, opt, fresh, progress, configs)) {
                scored[p] = std::move(pt);
            }
        }
        result.points.clear();  // the scored points in grid order (all of them for "grid")
        for (const Point& p : detail::GridPoints(opt.axes)) {
            if (const auto it = scored.find(p); it != scored.end()) {
                result.points.push_back(it->second);
            }
        }
        ChooseBest(result);
    };
    const auto unscored = [&](std::vector<Point> points) {
        points.erase(std::remove_if(points.begin(), points.end(),
                                    [&](const Point& p) { return scored.count(p) != 0; }),
                     points.end());
        return points;
    };
    if (opt.search == "descent") {
        Descend(opt, result, evaluate, unscored);
    } else {
        evaluate(detail::GridPoints(opt.axes));
        for (int round = 1; round <= opt.grow; ++round) {
            const std::vector<SweepGrowth> grown = Grow(opt, result.points[result.best], round);
            if (grown.empty()) {
                break;
            }
            result.growth.insert(result.growth.end(), grown.begin(), grown.end());
            evaluate(unscored(detail::GridPoints(opt.axes)));
        }
    }
    result.pareto = ParetoFront(result.points);
    for (const TrainRun& run : TrainingRuns(cx, opt)) {  // in run order; every run was scored
        if (const auto it = configs.find(run.name); it != configs.end()) {
            result.run_names.push_back(run.name);
            result.run_configs.push_back(it->second);
        }
    }
    if (options.HasHeldOut()) {
        result.held_out = HeldOut(cx, opt, result.points[result.best].values, progress);
    }
    result.options = opt;
    result.simulated_runs = cx.simulated_runs.load();
    result.paper_maps = cx.paper_maps.load();
    result.threads = cx.threads;
    result.ranks = cx.session->ranks();
    result.elapsed_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
}

}  // namespace casmap::pipeline
