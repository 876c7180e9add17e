#include "casmap/pipeline/sweep.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "casmap/core/input_error.hpp"

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

}  // namespace
}  // namespace casmap::pipeline
