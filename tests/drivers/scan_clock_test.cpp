// ScanClock on synthetic arrival sequences: true sweeps on a grid t0 + k T, seeded random
// one-sided latencies, skipped sweeps. Oracle: the lower envelope's definition, i.e. scan j is
// stamped t0 + k_j T + (smallest latency among the scans of the last window_s seconds).
#include "casmap/drivers/scan_clock.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "casmap/core/input_error.hpp"
#include "casmap/drivers/lms200_driver.hpp"

namespace casmap::drivers {
namespace {

constexpr double kT = 1.0 / 75.0;
constexpr double kT0 = 1795314568.0 + 0.00123;  // system-clock seconds: 0.24 us resolution

struct Arrivals {
    std::vector<std::int64_t> k;   // true grid index
    std::vector<double> latency;   // >= 0
    std::vector<double> latest_s;  // t0 + k T + latency
};

/// `count` scans; each sweep is skipped with probability `skip_p`, plus a run of 5 skipped
/// sweeps after scan 100. Latency: 0 with probability 0.1, else exponential (mean 0.7 ms)
/// capped at 5 ms, like the measured host latency at 500000 baud.
Arrivals MakeArrivals(std::uint64_t seed, int count, double skip_p, double period = kT) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::exponential_distribution<double> lat(1.0 / 0.0007);
    Arrivals a;
    std::int64_t k = 3;
    for (int i = 0; i < count; ++i) {
        while (u(rng) < skip_p) {
            ++k;
        }
        if (i == 100) {
            k += 5;
        }
        const double l = u(rng) < 0.1 ? 0.0 : std::min(lat(rng), 0.005);
        a.k.push_back(k);
        a.latency.push_back(l);
        a.latest_s.push_back(kT0 + static_cast<double>(k) * period + l);
        ++k;
    }
    return a;
}

/// Smallest latency among scans 0..j whose latest stamp is within `window_s` of scan j's.
double EnvelopeLatency(const Arrivals& a, std::size_t j, double window_s) {
    double m = a.latency[j];
    for (std::size_t i = 0; i < j; ++i) {
        if (a.latest_s[i] - kT0 >= a.latest_s[j] - kT0 - window_s) {
            m = std::min(m, a.latency[i]);
        }
    }
    return m;
}

TEST(ScanClock, StampsLandOnTheGridWithTheRightIndex) {
    for (const std::uint64_t seed : {1ULL, 42ULL, 20261122ULL}) {
        std::printf("ScanClock seed %llu\n", static_cast<unsigned long long>(seed));
        const Arrivals a = MakeArrivals(seed, 600, 0.05);
        ScanClock clock;
        int exact = 0;
        for (std::size_t j = 0; j < a.k.size(); ++j) {
            const double stamp = clock.Stamp(a.latest_s[j]);
            // Index counted from the first scan: skipped sweeps skip indices.
            ASSERT_EQ(clock.last_index(), a.k[j] - a.k[0]) << "seed " << seed << " scan " << j;
            const double truth = kT0 + static_cast<double>(a.k[j]) * kT;
            const double want = truth + EnvelopeLatency(a, j, 2.0);
            ASSERT_NEAR(stamp, want, 1e-6) << "seed " << seed << " scan " << j;
            ASSERT_NEAR(clock.phase_s() + static_cast<double>(clock.last_index()) * kT, stamp,
                        1e-6);
            if (std::abs(stamp - truth) < 1e-6) {
                ++exact;
            }
        }
        // A zero-latency scan appears within the first few: from then on every stamp is exact.
        EXPECT_GT(exact, 580) << "seed " << seed;
        EXPECT_EQ(clock.outliers(), 0U);
    }
}

TEST(ScanClock, InterleavedPeriodAndLongGaps) {
    const double period = 4.0 * kT;  // 100 deg / 0.25 deg: four turns per scan
    const Arrivals a = MakeArrivals(7, 300, 0.3, period);
    ScanClockConfig cc;
    cc.period_s = period;
    ScanClock clock(cc);
    for (std::size_t j = 0; j < a.k.size(); ++j) {
        const double stamp = clock.Stamp(a.latest_s[j]);
        ASSERT_EQ(clock.last_index(), a.k[j] - a.k[0]) << "scan " << j;
        ASSERT_NEAR(stamp, kT0 + static_cast<double>(a.k[j]) * period + EnvelopeLatency(a, j, 2.0),
                    1e-6);
    }
}

TEST(ScanClock, AVeryLateScanKeepsItsSlotAndDoesNotMoveThePhase) {
    ScanClock clock;
    for (int k = 0; k < 50; ++k) {
        (void)clock.Stamp(kT0 + k * kT);
    }
    // Late by 0.9 T (the host stalled): floor(0.9 + 0.25) would give the next slot.
    const double late = clock.Stamp(kT0 + 50 * kT + 0.9 * kT);
    EXPECT_EQ(clock.last_index(), 50);
    EXPECT_NEAR(late, kT0 + 50 * kT, 1e-6);
    EXPECT_EQ(clock.outliers(), 1U);
    EXPECT_NEAR(clock.Stamp(kT0 + 51 * kT + 0.0001), kT0 + 51 * kT, 1e-6);
    EXPECT_EQ(clock.last_index(), 51);
}

TEST(ScanClock, FollowsADriftingClockAndAStepBack) {
    // The host clock runs 300 ppm fast against the scanner's crystal; latency 0..0.2 ms.
    const double eps = 300e-6;
    std::mt19937_64 rng(5);
    std::printf("ScanClock drift seed 5\n");
    std::uniform_real_distribution<double> lat(0.0, 0.0002);
    ScanClock clock;
    double worst = 0.0;
    for (int k = 0; k < 1500; ++k) {  // 20 s
        const double truth = kT0 + k * kT * (1.0 + eps);
        const double stamp = clock.Stamp(truth + lat(rng));
        ASSERT_EQ(clock.last_index(), k);
        worst = std::max(worst, std::abs(stamp - truth));
    }
    // The envelope lags a rising offset by at most drift x window (0.6 ms) plus the latency.
    EXPECT_LT(worst, eps * 2.0 + 0.0002 + 1e-6);
    // The system clock steps back 4 ms: after confirm_scans scans the phase follows.
    const double step = -0.004;
    double last_err = 1.0;
    for (int k = 1500; k < 1520; ++k) {
        const double truth = kT0 + k * kT * (1.0 + eps) + step;
        last_err = std::abs(clock.Stamp(truth) - truth);
    }
    // Restarted at the third scan after the step; since then the drift adds 4 us per scan.
    EXPECT_LT(last_err, 18 * kT * eps + 1e-6);
    EXPECT_EQ(clock.outliers(), 2U);  // the first two scans after the step (confirm_scans 3)
}

TEST(ScanClock, ResetForgetsThePhase) {
    ScanClock clock;
    for (int k = 0; k < 20; ++k) {
        (void)clock.Stamp(kT0 + k * kT);
    }
    clock.Reset();
    const double t1 = kT0 + 100.0 + 0.005;  // a reconnect: the mirror restarted elsewhere
    EXPECT_NEAR(clock.Stamp(t1), t1, 1e-6);
    EXPECT_EQ(clock.last_index(), 0);
    EXPECT_NEAR(clock.Stamp(t1 + kT), t1 + kT, 1e-6);
    EXPECT_EQ(clock.last_index(), 1);
}

TEST(ScanClock, ConfigIsValidated) {
    ScanClockConfig cc;
    cc.period_s = 0.0;
    EXPECT_THROW(ScanClock{cc}, InputError);
    cc = {};
    cc.guard = 1.0;
    EXPECT_THROW(ScanClock{cc}, InputError);
    DriverConfig dc;
    dc.device = "/dev/ttyUSB0";
    EXPECT_EQ(dc.stamps, StampMode::kScanClock);  // on by default
    dc.sync_window_s = 0.0;
    EXPECT_THROW(dc.Validate(), InputError);
}

}  // namespace
}  // namespace casmap::drivers
