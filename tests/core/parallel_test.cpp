#include "casmap/core/parallel.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

namespace casmap::core {
namespace {

TEST(ParallelFor, EveryItemOnceAtAnyThreadCount) {
    for (const int threads : {1, 2, 7}) {
        std::vector<int> hits(1000, 0);
        ParallelFor(hits.size(), threads, [&](std::size_t i) { hits[i] += 1; });
        for (const int h : hits) {
            EXPECT_EQ(h, 1);
        }
    }
}

TEST(ParallelFor, RethrowsTheWorkersException) {
    EXPECT_THROW(ParallelFor(100, 2,
                             [](std::size_t i) {
                                 if (i == 50) throw std::runtime_error("boom");
                             }),
                 std::runtime_error);
}

}  // namespace
}  // namespace casmap::core
