#include "casmap/pipeline/sweep.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

#include "casmap/core/input_error.hpp"
#include "casmap/pipeline/map_run.hpp"
#include "tests/temp_dir.hpp"

namespace casmap::pipeline {
namespace {

std::string ErrorOf(const std::function<void()>& fn) {
    try {
        fn();
    } catch (const InputError& e) {
        return e.what();
    }
    return "(no error)";
}

TEST(ParseSweepAxis, ExpandsFromToStep) {
    const SweepAxis a = ParseSweepAxis("A=6:12:3", "axes");
    EXPECT_EQ(a.name, "A");
    EXPECT_EQ(a.values, (std::vector<double>{6.0, 9.0, 12.0}));
    // A step that does not divide the range stops at or below TO.
    EXPECT_EQ(ParseSweepAxis("B=0.02:0.05:0.02", "axes").values.size(), 2U);
    // Values carry no binary noise: 0.07 + 2 x 0.02 is written 0.11, not 0.11000000000000001.
    EXPECT_EQ(ParseSweepAxis("B=0.07:0.11:0.02", "axes").values,
              (std::vector<double>{0.07, 0.09, 0.11}));
}

TEST(ParseSweepAxis, RejectsNamingTheCallersField) {
    EXPECT_NE(ErrorOf([] { (void)ParseSweepAxis("A=10:5:1", "f"); }).find("inverted"),
              std::string::npos);
    EXPECT_NE(ErrorOf([] { (void)ParseSweepAxis("A=1:5:0", "f"); }).find("STEP"),
              std::string::npos);
    EXPECT_NE(ErrorOf([] { (void)ParseSweepAxis("Q=1:5:1", "f"); }).find("f = Q"),
              std::string::npos);
    EXPECT_NE(ErrorOf([] { (void)ParseSweepAxis("B=1:x:1", "f"); }).find("B=1:x:1"),
              std::string::npos);
    EXPECT_NE(ErrorOf([] { (void)ParseSweepAxis("B", "f"); }).find("NAME=FROM:TO:STEP"),
              std::string::npos);
}

TEST(SweepOptions, DefaultsAreValid) { EXPECT_NO_THROW(SweepOptions{}.Validate()); }

TEST(SweepOptions, RejectsBadAxesNamingTheField) {
    SweepOptions twice;
    twice.axes = {{"A", {6.0}}, {"A", {7.0}}};
    EXPECT_NE(ErrorOf([&] { twice.Validate(); }).find("axes = A (parameter given twice)"),
              std::string::npos);
    SweepOptions speed;
    speed.axes = {{"speed", {0.5, 1.5}}};
    EXPECT_NE(ErrorOf([&] { speed.Validate(); }).find("speed=1.5"), std::string::npos);
    SweepOptions a;
    a.axes = {{"a", {2.5}}};
    EXPECT_NE(ErrorOf([&] { a.Validate(); }).find("integer"), std::string::npos);
    SweepOptions fixed;
    fixed.fixed = {"bogus=1"};
    EXPECT_NE(ErrorOf([&] { fixed.Validate(); }).find("bogus"), std::string::npos);
}

// A mapping stage's parameter is an axis only for a pipeline that runs the stage.
TEST(SweepOptions, StageAxesNeedAPipelineRunningTheStage) {
    for (const auto& [filter, axis] : std::vector<std::pair<std::string, std::string>>{
             {"cas", "shadow.min_angle_deg"},
             {"range_jump_cas", "shadow.min_angle_deg"},
             {"shadow_cas", "range_jump.jump_min_m"},
             {"range_jump_cas", "sweep_jump.max_angle_deg"},
             {"sweep_jump_cas", "range_jump.jump_min_m"},
             {"cas_trail", "kalman.mahalanobis_gate"}}) {
        SweepOptions o;
        o.filter = filter;
        o.courses = {4};
        o.axes = {{axis, {20.0}}};
        try {
            o.Validate();
            ADD_FAILURE() << filter << " accepted the axis " << axis;
        } catch (const InputError& e) {
            EXPECT_EQ(e.field(), "axes") << e.what();
            EXPECT_EQ(e.value(), axis) << e.what();
            EXPECT_NE(e.rule().find("does not run"), std::string::npos) << e.what();
        }
    }
    SweepOptions ok;
    ok.filter = "kalman_median";
    ok.courses = {4};
    ok.axes = {{"kalman.mahalanobis_gate", {1.0, 2.5}}};
    EXPECT_NO_THROW(ok.Validate());
    ok.axes = {{"kalman.mahalanobis_gate", {0.0}}};  // out of range: the parameter is named
    EXPECT_NE(ErrorOf([&] { ok.Validate(); }).find("kalman.mahalanobis_gate"), std::string::npos);
    SweepOptions sweep_jump;
    sweep_jump.filter = "sweep_jump_hybrid";
    sweep_jump.courses = {4};
    sweep_jump.axes = {{"sweep_jump.max_angle_deg", {5.0, 15.0}}};
    EXPECT_NO_THROW(sweep_jump.Validate());
    sweep_jump.axes = {{"sweep_jump.max_angle_deg", {90.0}}};
    EXPECT_NE(ErrorOf([&] { sweep_jump.Validate(); }).find("sweep_jump.max_angle_deg"),
              std::string::npos);
    EXPECT_EQ(ParseSweepAxis("shadow.window=1:3:1", "f").values,
              (std::vector<double>{1.0, 2.0, 3.0}));
}

TEST(Summarise, IgnoresNonFiniteValues) {
    const SweepStats s = Summarise({1.0, 3.0, std::nan("")});
    EXPECT_EQ(s.runs, 2U);
    EXPECT_DOUBLE_EQ(s.mean, 2.0);
    EXPECT_DOUBLE_EQ(s.std, 1.0);
    EXPECT_DOUBLE_EQ(s.min, 1.0);
    EXPECT_DOUBLE_EQ(s.max, 3.0);
    EXPECT_TRUE(std::isnan(Summarise({}).mean));
}

// Two points on one run: `a` re-maps, A re-filters; the best point has the lowest mean PI and
// the result does not depend on the thread count.
TEST(RunSweep, ScoresEveryPointOnceAndPicksTheBest) {
    SweepOptions options;
    options.axes = {{"A", {6.0, 12.0}}, {"a", {2.0, 3.0}}};
    options.courses = {4};
    options.threads = 1;
    std::size_t calls = 0;
    const SweepResult one = RunSweep(options, [&](std::size_t done, std::size_t total) {
        EXPECT_EQ(total, 1U);
        EXPECT_EQ(done, 1U);
        ++calls;
    });
    EXPECT_EQ(calls, 1U);
    ASSERT_EQ(one.points.size(), 4U);
    EXPECT_EQ(one.points[1].values, (std::vector<double>{6.0, 3.0}));
    for (const SweepPoint& p : one.points) {
        EXPECT_EQ(p.pi.runs, 1U);
        EXPECT_TRUE(std::isfinite(p.pi.mean));
        EXPECT_LE(one.points[one.best].pi.mean, p.pi.mean);
        EXPECT_GE(p.spikes_mean, 0.0);
        EXPECT_LE(p.runs_all_poles_kept, 1U);
    }
    // a = 3 maps like the bench (same CAS parameters): the same spikes as ScoreRun's CAS.
    BenchOptions bench;
    bench.courses = {4};
    bench.tests = {"T"};
    bench.sheets = false;
    bench.filter_settings = {"A=6"};
    const BenchRun run = RunBench(bench).runs.at(0);
    EXPECT_EQ(one.points[1].spikes_mean, static_cast<double>(run.filters.at("cas").spikes));
    EXPECT_EQ(one.points[1].runs_all_poles_kept,
              run.poles_kept.at("cas").size() == run.poles.size() ? 1U : 0U);
    EXPECT_EQ(one.run_names, (std::vector<std::string>{"course04_T"}));
    options.threads = 2;
    SweepResult two = RunSweep(options);
    two.elapsed_s = one.elapsed_s;
    two.threads = one.threads;
    EXPECT_EQ(SweepJson(one), SweepJson(two));
}

TEST(ParseSeeds, ListsAndRanges) {
    EXPECT_EQ(ParseSeeds("3,7", "f"), (std::vector<std::uint64_t>{3, 7}));
    EXPECT_EQ(ParseSeeds("1-3,2", "f"), (std::vector<std::uint64_t>{1, 2, 3}));
    EXPECT_NE(ErrorOf([] { (void)ParseSeeds("x", "--train-seeds"); }).find("--train-seeds = x"),
              std::string::npos);
    EXPECT_NE(ErrorOf([] { (void)ParseSeeds("3-1", "f"); }).find("FROM <= TO"), std::string::npos);
    EXPECT_NE(ErrorOf([] { (void)ParseSeeds("", "f"); }).find("expected seeds"), std::string::npos);
}

TEST(SweepOptions, RejectsHeldOutRunsThatAreTrainingRuns) {
    SweepOptions same;
    same.seeds = {1, 2};
    same.test_seeds = {2, 3};
    EXPECT_NE(ErrorOf([&] { same.Validate(); }).find("test_seeds = seed 2, course 1"),
              std::string::npos);
    SweepOptions courses;  // held-out courses, same seed: allowed when disjoint
    courses.courses = {1, 2};
    courses.test_courses = {3};
    EXPECT_NO_THROW(courses.Validate());
    courses.test_courses = {2};
    EXPECT_NE(ErrorOf([&] { courses.Validate(); }).find("test_courses"), std::string::npos);
    SweepOptions filter;
    filter.filter = "bogus";
    EXPECT_NE(ErrorOf([&] { filter.Validate(); }).find("filter = bogus"), std::string::npos);
    SweepOptions grow;
    grow.grow = 21;
    EXPECT_NE(ErrorOf([&] { grow.Validate(); }).find("grow"), std::string::npos);
    SweepOptions trail;  // a variant's parameter out of its range names the axis
    trail.filter = "cas_trail";
    trail.axes = {{"support_min", {-1.0}}};
    EXPECT_NE(ErrorOf([&] { trail.Validate(); }).find("support_min"), std::string::npos);
}

// Training on seed 1, held out on seed 2; the grid grows while the best sits on an edge; the
// chosen point keeps every pole if any point does; the Pareto front is exactly the
// non-dominated points; the paper's figures on the held-out run are the bench's.
TEST(RunSweep, GrowsChoosesOnTrainingAndScoresHeldOut) {
    SweepOptions options;
    options.axes = {{"A", {12.0, 24.0}}, {"h_sum_min", {7.0, 9.0}}};
    options.courses = {4};
    options.test_seeds = {2};
    options.grow = 2;
    options.threads = 2;
    const SweepResult r = RunSweep(options);
    const std::size_t na = r.options.axes[0].values.size();
    const std::size_t nh = r.options.axes[1].values.size();
    ASSERT_EQ(r.points.size(), na * nh);
    EXPECT_FALSE(r.growth.empty());  // A = 24 beats A = 12 at the paper's h_sum_min
    EXPECT_LE(r.growth.back().round, 2);
    for (const SweepGrowth& g : r.growth) {
        const auto& values = g.axis == "A" ? r.options.axes[0].values : r.options.axes[1].values;
        EXPECT_NE(std::find(values.begin(), values.end(), g.added.front()), values.end());
    }
    const SweepPoint& best = r.points[r.best];
    bool any_keeps = false;
    for (const SweepPoint& p : r.points) {
        EXPECT_EQ(p.runs_scored, 1U);
        any_keeps = any_keeps || p.KeepsEveryPole();
        if (p.KeepsEveryPole()) {
            EXPECT_LE(best.pi.mean, p.pi.mean);
        }
    }
    EXPECT_EQ(r.best_keeps_every_pole, any_keeps);
    EXPECT_EQ(best.KeepsEveryPole(), any_keeps);
    const auto dominates = [](const SweepPoint& q, const SweepPoint& p) {
        return q.pi.mean <= p.pi.mean && q.poles_kept >= p.poles_kept &&
               q.spikes_total <= p.spikes_total &&
               (q.pi.mean < p.pi.mean || q.poles_kept > p.poles_kept ||
                q.spikes_total < p.spikes_total);
    };
    for (std::size_t i = 0; i < r.points.size(); ++i) {
        const bool in_front = std::find(r.pareto.begin(), r.pareto.end(), i) != r.pareto.end();
        bool dominated = false;
        for (const SweepPoint& q : r.points) {
            dominated = dominated || dominates(q, r.points[i]);
        }
        EXPECT_EQ(in_front, !dominated) << i;
    }
    ASSERT_EQ(r.held_out.size(), 1U);
    EXPECT_EQ(r.held_out[0].name, "seed2_course04_T");
    BenchOptions bench;
    bench.courses = {4};
    bench.tests = {"T"};
    bench.seed = 2;
    bench.sheets = false;
    const BenchRun paper = RunBench(bench).runs.at(0);
    EXPECT_EQ(r.held_out[0].paper.pi, paper.filters.at("cas").pi);
    EXPECT_EQ(r.held_out[0].paper.spikes, paper.filters.at("cas").spikes);
    bench.filter_settings = {"A=" + FormatNumber(best.values[0]),
                             "h_sum_min=" + FormatNumber(best.values[1])};
    const BenchRun chosen = RunBench(bench).runs.at(0);
    EXPECT_EQ(r.held_out[0].chosen.pi, chosen.filters.at("cas").pi);
    EXPECT_EQ(r.held_out[0].chosen.poles_kept, chosen.poles_kept.at("cas").size());
    // The same at one thread, byte for byte.
    options.threads = 1;
    SweepResult one = RunSweep(options);
    one.elapsed_s = r.elapsed_s;
    one.threads = r.threads;
    EXPECT_EQ(SweepJson(one), SweepJson(r));
}

// Coordinate descent scores a subset of the grid, each point exactly as the grid sweep does,
// and its best point is the rule's best among the points it scored.
TEST(RunSweep, DescentScoresASubsetLikeTheGrid) {
    SweepOptions options;
    options.axes = {{"A", {10.0, 20.0, 30.0, 40.0}}, {"h_sum_min", {6.0, 8.0, 10.0}}};
    options.courses = {4};
    options.threads = 2;
    const SweepResult grid = RunSweep(options);
    options.search = "descent";
    const SweepResult descent = RunSweep(options);
    ASSERT_FALSE(descent.path.empty());
    EXPECT_EQ(descent.path.front().pass, 1);
    EXPECT_EQ(descent.path.back().best, descent.points[descent.best].values);
    EXPECT_LT(descent.points.size(), grid.points.size());
    for (const SweepPoint& p : descent.points) {
        const auto same = std::find_if(grid.points.begin(), grid.points.end(),
                                       [&](const SweepPoint& g) { return g.values == p.values; });
        ASSERT_NE(same, grid.points.end());
        EXPECT_EQ(same->pi.mean, p.pi.mean);
        EXPECT_EQ(same->poles_kept, p.poles_kept);
        EXPECT_EQ(same->spikes_total, p.spikes_total);
        if (p.KeepsEveryPole() && descent.best_keeps_every_pole) {
            EXPECT_LE(descent.points[descent.best].pi.mean, p.pi.mean);
        }
    }
    SweepOptions bad;
    bad.search = "random";
    EXPECT_NE(ErrorOf([&] { bad.Validate(); }).find("search = random"), std::string::npos);
}

// A variant's own parameter is swept with that variant (cas_trail's support_min changes PI).
TEST(RunSweep, SweepsAVariantsParameters) {
    SweepOptions options;
    options.filter = "cas_trail";
    options.axes = {{"support_min", {1.0, 8.0}}};
    options.courses = {4};
    options.threads = 2;
    const SweepResult r = RunSweep(options);
    ASSERT_EQ(r.points.size(), 2U);
    EXPECT_NE(r.points[0].pi.mean, r.points[1].pi.mean);
    EXPECT_NE(SweepJson(r).find("\"filter\":\"cas_trail\""), std::string::npos);
}

// Any bench pipeline can be swept: range_jump_cas maps the pre-filtered scans again; its
// figures equal casmap bench's for that pipeline at the same parameters.
TEST(RunSweep, SweepsANamedPipelineLikeTheBenchScoresIt) {
    SweepOptions options;
    options.filter = "range_jump_cas";
    options.axes = {{"A", {12.0, 20.0}}};
    options.courses = {4};
    options.threads = 2;
    const SweepResult r = RunSweep(options);
    ASSERT_EQ(r.points.size(), 2U);
    BenchOptions bench;
    bench.courses = {4};
    bench.tests = {"T"};
    bench.sheets = false;
    bench.pipelines = {"range_jump_cas"};
    bench.filter_settings = {"A=20"};
    const BenchRun run = RunBench(bench).runs.at(0);
    EXPECT_EQ(r.points[1].pi.mean, run.filters.at("range_jump_cas").pi);
    EXPECT_EQ(r.points[1].spikes_total, run.filters.at("range_jump_cas").spikes);
    EXPECT_EQ(r.points[1].poles_kept, run.poles_kept.at("range_jump_cas").size());
    EXPECT_TRUE(std::isnan(r.points[1].mixed_pct));  // no Table II shares for pipelines
}

// A pre-filter's parameter swept over a named pipeline: each point's figures equal casmap
// bench's for that pipeline with the value set (the stage's map is made with it).
TEST(RunSweep, SweepsAPreFilterParameterLikeTheBenchScoresIt) {
    SweepOptions options;
    options.filter = "shadow_cas";
    options.axes = {{"shadow.min_angle_deg", {5.0, 25.0}}};
    options.courses = {4};
    options.threads = 2;
    const SweepResult r = RunSweep(options);
    ASSERT_EQ(r.points.size(), 2U);
    EXPECT_NE(r.points[0].pi.mean, r.points[1].pi.mean);
    for (std::size_t i = 0; i < 2; ++i) {
        BenchOptions bench;
        bench.courses = {4};
        bench.tests = {"T"};
        bench.sheets = false;
        bench.pipelines = {"shadow_cas"};
        bench.filter_settings = {"shadow.min_angle_deg=" + FormatNumber(r.points[i].values[0])};
        const BenchRun run = RunBench(bench).runs.at(0);
        EXPECT_EQ(r.points[i].pi.mean, run.filters.at("shadow_cas").pi) << i;
        EXPECT_EQ(r.points[i].spikes_total, run.filters.at("shadow_cas").spikes) << i;
        EXPECT_EQ(r.points[i].poles_kept, run.poles_kept.at("shadow_cas").size()) << i;
    }
}

// The run cache (simulated scans, paper maps, pre-filter / Kalman maps kept across points and
// rounds) changes nothing: a sweep over a pre-filter parameter and a filter parameter with
// growth rounds, and a descent over a Kalman parameter, give the same result byte for byte
// as the uncached path (every run simulated each round, every point mapped anew).
TEST(RunSweep, RunCacheGivesTheUncachedResultByteForByte) {
    const auto both = [](SweepOptions options) {
        options.cache_runs = true;
        SweepResult cached = RunSweep(options);
        options.cache_runs = false;
        const SweepResult uncached = RunSweep(options);
        cached.elapsed_s = uncached.elapsed_s;
        EXPECT_EQ(SweepJson(cached), SweepJson(uncached)) << options.filter;
        EXPECT_EQ(cached.run_configs, uncached.run_configs) << options.filter;
        // The cache did its work: each training run simulated once (the uncached path once per
        // round), each paper map made once per run and `a`.
        const std::size_t runs = cached.run_names.size();
        EXPECT_EQ(cached.simulated_runs, runs) << options.filter;
        EXPECT_GT(uncached.simulated_runs, cached.simulated_runs) << options.filter;
        EXPECT_GT(uncached.paper_maps, cached.paper_maps) << options.filter;
        return cached;
    };
    SweepOptions jump;
    jump.filter = "range_jump_cas";
    jump.axes = {{"range_jump.jump_min_m", {0.1, 0.2}}, {"A", {12.0, 24.0}}};
    jump.courses = {4};
    jump.tests = {"T", "TP"};
    jump.test_seeds = {2};
    jump.grow = 1;
    jump.threads = 2;
    const SweepResult r = both(jump);
    EXPECT_EQ(r.points.front().runs_scored, 2U);
    EXPECT_NE(r.points[0].pi.mean, r.points[2].pi.mean);  // jump_min_m 0.1 vs 0.2 at A 12
    SweepOptions kalman;
    kalman.filter = "kalman_median";
    kalman.search = "descent";
    kalman.axes = {{"kalman.mahalanobis_gate", {1.0, 2.5, 4.0}}, {"a", {2.0, 3.0}}};
    kalman.courses = {4};
    kalman.grow = 1;
    kalman.threads = 2;
    const SweepResult k = both(kalman);
    EXPECT_FALSE(k.path.empty());
    SweepOptions trail;  // the direct filters' cache of paper maps, across growth rounds
    trail.filter = "cas_trail";
    trail.axes = {{"support_min", {5.0, 9.0}}};
    trail.courses = {4};
    trail.grow = 2;
    trail.threads = 2;
    (void)both(trail);
}

TEST(RunSweepToFolder, WritesTheOutputsAndTheJsonCopyOnRankZero) {
    const casmap::test::TempDir tmp("pipeline_sweep_folder");
    const std::filesystem::path& dir = tmp.Path();
    SweepOptions options;
    options.axes = {{"A", {6.0, 12.0}}};
    options.courses = {4};
    options.threads = 1;
    const std::optional<SweepResult> r =
        RunSweepToFolder(options, dir / "out", (dir / "copy.json").string());
    ASSERT_TRUE(r.has_value());  // one rank without mpirun
    EXPECT_EQ(r->ranks, 1);
    EXPECT_EQ(r->options.session, nullptr);
    EXPECT_EQ(r->points.size(), 2U);
    std::ifstream a(dir / "out" / "sweep.json");
    std::ifstream b(dir / "copy.json");
    const std::string written((std::istreambuf_iterator<char>(a)), {});
    const std::string copy((std::istreambuf_iterator<char>(b)), {});
    EXPECT_FALSE(written.empty());
    EXPECT_EQ(written, copy);
    // A copy in a missing folder fails before any work, naming the path and the field.
    try {
        (void)RunSweepToFolder(options, dir / "out2", (dir / "missing" / "c.json").string());
        ADD_FAILURE() << "no InputError";
    } catch (const InputError& e) {
        EXPECT_EQ(e.field(), "json");
        EXPECT_EQ(e.where(), (dir / "missing" / "c.json").string());
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "out2"));
}

}  // namespace
}  // namespace casmap::pipeline
