// Run files need strictly increasing scan stamps (io::ReadRunFile rejects others), so the scan
// clock must never stamp a scan at or before its predecessor, even when its phase estimate
// steps back by more than a period (latencies that suddenly shrink under host load).
#include <gtest/gtest.h>

#include <vector>

#include "casmap/drivers/scan_clock.hpp"

namespace casmap::drivers {
namespace {

TEST(ScanClockOrder, StampsIncreaseStrictlyWhenLatencyDropsByMoreThanAPeriod) {
    ScanClockConfig config;
    ScanClock clock(config);
    const double period = config.period_s;
    std::vector<double> stamps;
    for (int k = 0; k < 40; ++k) {  // 30 ms late for a while ...
        stamps.push_back(clock.Stamp(100.0 + k * period + 0.030));
    }
    for (int k = 40; k < 80; ++k) {  // ... then on time: the phase moves back by 30 ms > T
        stamps.push_back(clock.Stamp(100.0 + k * period));
    }
    for (std::size_t i = 1; i < stamps.size(); ++i) {
        EXPECT_GT(stamps[i], stamps[i - 1]) << "scan " << i;
    }
}

}  // namespace
}  // namespace casmap::drivers
