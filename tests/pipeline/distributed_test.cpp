#include "casmap/pipeline/distributed.hpp"

#include <gtest/gtest.h>

#include <set>

namespace casmap::pipeline {
namespace {

TEST(DistributeWork, EveryItemOnceWithItsPayloadAtAnyThreadCount) {
    const std::vector<std::size_t> items = {7, 3, 11, 0, 5};
    for (const int threads : {1, 2, 3}) {
        std::multiset<std::size_t> done;
        const auto payloads = DistributeWork(
            DistributedSession::Local(), items, threads,
            [](std::size_t i) { return "item " + std::to_string(i * i); },
            [&](std::size_t i, const std::string&) { done.insert(i); });
        ASSERT_EQ(payloads.size(), items.size()) << threads << " threads";
        for (const std::size_t i : items) {
            EXPECT_EQ(payloads.at(i), "item " + std::to_string(i * i));
            EXPECT_EQ(done.count(i), 1U);
        }
    }
}

TEST(DistributedSession, LocalIsRankZeroOfOne) {
    const DistributedSession session = DistributedSession::Local();
    EXPECT_EQ(session.rank(), 0);
    EXPECT_EQ(session.ranks(), 1);
    session.Barrier();
}

}  // namespace
}  // namespace casmap::pipeline
