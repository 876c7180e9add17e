// RunSweep (sweep.hpp): the search over the grid (every point, or coordinate descent) with
// growth of edge axes, then the held-out scoring of the chosen point beside the paper's CAS.
// The runs and their rounds are in sweep_train.cpp (payloads: sweep_payload.cpp); the choice of
// the best point, the Pareto front and the growth in sweep_search.cpp.
#include <algorithm>
#include <chrono>
#include <map>
#include <string>
#include <vector>

#include "casmap/core/parallel.hpp"
#include "casmap/pipeline/bench_pipelines.hpp"
#include "casmap/pipeline/distributed.hpp"
#include "casmap/pipeline/sweep.hpp"
#include "casmap/pipeline/sweep_detail.hpp"
#include "casmap/pipeline/sweep_search.hpp"
#include "casmap/pipeline/sweep_train.hpp"

namespace casmap::pipeline {
namespace {

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
    detail::Point current;
    for (const SweepAxis& axis : opt.axes) {
        current.push_back(axis.values[(axis.values.size() - 1) / 2]);
    }
    evaluate(unscored({current}));
    int rounds = 0;
    for (int pass = 1; pass <= kMaxPasses; ++pass) {
        const detail::Point before = result.points[result.best].values;
        for (std::size_t i = 0; i < opt.axes.size(); ++i) {
            for (;;) {
                current = result.points[result.best].values;
                std::vector<detail::Point> line;
                for (const double v : opt.axes[i].values) {
                    line.push_back(current);
                    line.back()[i] = v;
                }
                evaluate(unscored(line));
                if (rounds >= opt.grow) {
                    break;
                }
                const std::vector<SweepGrowth> grown =
                    detail::Grow(opt, result.points[result.best], rounds + 1, static_cast<int>(i));
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
    detail::Context cx(options);
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
    std::map<detail::Point, SweepPoint> scored;
    std::map<std::string, std::string> configs;  // per training run name
    const auto evaluate = [&](const std::vector<detail::Point>& fresh) {
        if (!fresh.empty()) {
            for (auto& [p, pt] : detail::TrainRound(cx, opt, fresh, progress, configs)) {
                scored[p] = std::move(pt);
            }
        }
        result.points.clear();  // the scored points in grid order (all of them for "grid")
        for (const detail::Point& p : detail::GridPoints(opt.axes)) {
            if (const auto it = scored.find(p); it != scored.end()) {
                result.points.push_back(it->second);
            }
        }
        detail::ChooseBest(result);
    };
    const auto unscored = [&](std::vector<detail::Point> points) {
        points.erase(std::remove_if(points.begin(), points.end(),
                                    [&](const detail::Point& p) { return scored.count(p) != 0; }),
                     points.end());
        return points;
    };
    if (opt.search == "descent") {
        Descend(opt, result, evaluate, unscored);
    } else {
        evaluate(detail::GridPoints(opt.axes));
        for (int round = 1; round <= opt.grow; ++round) {
            const std::vector<SweepGrowth> grown =
                detail::Grow(opt, result.points[result.best], round);
            if (grown.empty()) {
                break;
            }
            result.growth.insert(result.growth.end(), grown.begin(), grown.end());
            evaluate(unscored(detail::GridPoints(opt.axes)));
        }
    }
    result.pareto = detail::ParetoFront(result.points);
    // In run order; every run was scored.
    for (const detail::TrainRun& run : detail::TrainingRuns(cx, opt)) {
        if (const auto it = configs.find(run.name); it != configs.end()) {
            result.run_names.push_back(run.name);
            result.run_configs.push_back(it->second);
        }
    }
    if (options.HasHeldOut()) {
        result.held_out = detail::HeldOut(cx, opt, result.points[result.best].values, progress);
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
