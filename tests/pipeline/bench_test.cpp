#include "casmap/pipeline/bench.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "casmap/core/input_error.hpp"
#include "casmap/pipeline/bench_runner.hpp"

namespace casmap::pipeline {
namespace {

/// The InputError `options.Validate()` throws (fails the test if none).
InputError ValidationError(const BenchOptions& options) {
    try {
        options.Validate();
    } catch (const InputError& e) {
        return e;
    }
    ADD_FAILURE() << "expected InputError";
    return InputError("");
}

TEST(BenchOptions, DefaultsAreValid) { EXPECT_NO_THROW(BenchOptions{}.Validate()); }

TEST(BenchOptions, DefaultsArePaperBenchmark) {
    const BenchOptions o;
    EXPECT_EQ(o.courses.size(), 16U);
    EXPECT_EQ(o.tests, (std::vector<std::string>{"T", "TR", "TP", "TRP"}));
    EXPECT_EQ(o.seed, 1U);
}

TEST(BenchOptions, RejectedFieldsAreNamedWithoutFlags) {
    struct Case {
        BenchOptions options;
        std::string field;
        std::string text;
    };
    std::vector<Case> cases(6);
    cases[0].options.courses = {0};
    cases[0].field = "courses";
    cases[1].options.courses = {4, 4};
    cases[1].field = "courses";
    cases[2].options.tests = {"T", "XY"};
    cases[2].field = "tests";
    cases[3].options.courses_dir = "/nonexistent";
    cases[3].field = "courses_dir";
    cases[4].options.filter_settings = {"nope=1"};
    cases[4].text = "nope";
    cases[5].options.tests = {};
    cases[5].field = "tests";
    for (const Case& c : cases) {
        const InputError e = ValidationError(c.options);
        const std::string what = e.what();
        if (!c.field.empty()) {
            EXPECT_EQ(e.field(), c.field) << what;
        }
        EXPECT_NE(what.find(c.text), std::string::npos) << what;
        EXPECT_EQ(what.find("--courses"), std::string::npos) << what;
        EXPECT_EQ(what.find("--tests"), std::string::npos) << what;
    }
}

TEST(ParseCourses, RangesListsAndErrorsNamingTheCallersField) {
    EXPECT_EQ(ParseCourses("1,3,7-9", "courses"), (std::vector<int>{1, 3, 7, 8, 9}));
    EXPECT_EQ(ParseCourses("4,4", "courses"), (std::vector<int>{4}));
    EXPECT_THROW((void)ParseCourses("0", "courses"), InputError);
    try {
        (void)ParseCourses("9-3", "my_field");
        FAIL();
    } catch (const InputError& e) {
        EXPECT_EQ(e.field(), "my_field");
        EXPECT_NE(std::string(e.what()).find("inverted"), std::string::npos);
    }
    EXPECT_EQ(ParseTests("TRP,T", "tests"), (std::vector<std::string>{"T", "TRP"}));
}

// One course x test through the library: the figures do not depend on the thread count,
// progress reaches total, and the report names every filter.
TEST(RunBench, OneRunIsThreadIndependentAndReportsProgress) {
    BenchOptions options;
    options.courses = {4};
    options.tests = {"T"};
    options.seed = 3;
    options.sheets = false;
    options.threads = 1;
    std::vector<std::size_t> seen;
    const BenchResult one = RunBench(options, [&](std::size_t done, std::size_t total) {
        EXPECT_EQ(total, 1U);
        seen.push_back(done);
    });
    EXPECT_EQ(seen, (std::vector<std::size_t>{1}));
    ASSERT_EQ(one.runs.size(), 1U);
    EXPECT_TRUE(one.sheets.empty());
    EXPECT_EQ(one.run_names, (std::vector<std::string>{"course04_T"}));
    EXPECT_NE(one.run_configs[0].find("filters:\n  cas: {k: 2"), std::string::npos);
    const BenchRun& run = one.runs[0];
    EXPECT_EQ(run.course, 4);
    EXPECT_EQ(run.test, "T");
    EXPECT_GT(run.scans, 100);
    for (const std::string& name : BenchFilterNames()) {
        ASSERT_EQ(run.filters.count(name), 1U) << name;
        EXPECT_TRUE(std::isfinite(run.filters.at(name).pi)) << name;
    }
    options.threads = 2;
    const BenchResult two = RunBench(options);
    EXPECT_EQ(BenchJson(one.runs, 0.0, 1), BenchJson(two.runs, 0.0, 1));
}

}  // namespace
}  // namespace casmap::pipeline
