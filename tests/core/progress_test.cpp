#include "casmap/core/progress.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "casmap/core/input_error.hpp"
#include "casmap/core/parallel.hpp"

namespace casmap::core {
namespace {

TEST(ProgressCounter, ReportsEveryUnitInOrderFromWorkers) {
    std::vector<std::size_t> seen;
    ProgressCounter counter(
        [&](std::size_t done, std::size_t total) {
            EXPECT_EQ(total, 50U);
            seen.push_back(done);  // never concurrent: no lock needed here
        },
        50);
    ParallelFor(50, 4, [&](std::size_t) { counter.Advance(); });
    ASSERT_EQ(seen.size(), 50U);
    for (std::size_t i = 0; i < seen.size(); ++i) {
        EXPECT_EQ(seen[i], i + 1);
    }
}

TEST(ProgressCounter, EmptyFunctionIsNoReporting) {
    ProgressCounter counter(ProgressFn{}, 3);
    counter.Advance(3);  // must not call an empty std::function
    SUCCEED();
}

TEST(InputError, WithFieldRenamesOnlyTheField) {
    const InputError e = MakeInputError("a.yaml:3:1", "courses", "17", "allowed: 1..16");
    EXPECT_EQ(std::string(e.what()), "a.yaml:3:1: courses = 17 (allowed: 1..16)");
    EXPECT_EQ(e.field(), "courses");
    EXPECT_EQ(std::string(e.WithField("--courses").what()),
              "a.yaml:3:1: --courses = 17 (allowed: 1..16)");
    const InputError plain("just a message");
    EXPECT_EQ(std::string(plain.WithField("--x").what()), "just a message");
}

}  // namespace
}  // namespace casmap::core
