// What the driver does with its arrival times when the host stalls, on synthetic arrivals (no
// pty, no real time, so the outcome never depends on the machine's load): a backlog read at
// once is bounded telegram by telegram (BoundArrivalsInRead) and keeps its sweep slots, and a
// late scan in the scan clock's warm-up no longer puts the held scans before it a period early
// (ReslotHeldScans).
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "casmap/drivers/scan_clock.hpp"
#include "casmap/drivers/scan_codec.hpp"

namespace casmap::drivers {
namespace {

constexpr double kPeriodS = 1.0 / 75.0;   // 1 degree: a sweep every 13.3 ms
constexpr double kT0 = 1.8e9 + 0.3;       // beam 0 of sweep 0, seconds since 1970
constexpr std::size_t kFrameBytes = 372;  // 181 values at 500000 baud: 7.44 ms on the line

double Beam0(int sweep) { return kT0 + sweep * kPeriodS; }
/// When the telegram of `sweep` has left the line (sent when its sweep is complete).
double LineEnd(int sweep) {
    return Beam0(sweep) + SweepDurationS(Variant{}) + TransmissionTimeS(kFrameBytes, 500000);
}
/// The driver's latest beam-0 stamp for a telegram that arrived at `arrival_s`.
double Latest(double arrival_s) {
    return arrival_s - TransmissionTimeS(kFrameBytes, 500000) - SweepDurationS(Variant{});
}

/// Stamp errors of sweeps 0..39: read on time (50 us late) except 20..26, which wait in the
/// pty while the host stalls and are read at once 2 ms after the last of them ended.
std::vector<double> BacklogErrors(bool bounded) {
    ScanClock clock;
    std::vector<double> errors;
    const auto stamp = [&](int sweep, double arrival_s) {
        errors.push_back(clock.Stamp(Latest(arrival_s)) - Beam0(sweep));
    };
    for (int j = 0; j < 20; ++j) {
        stamp(j, LineEnd(j) + 5e-5);
    }
    const double read_s = LineEnd(26) + 0.002;
    std::vector<ReadTelegram> backlog;
    for (int j = 20; j <= 26; ++j) {
        const double after = static_cast<double>((26 - j) * kFrameBytes);
        backlog.push_back({read_s - (bounded ? after * ByteTimeS(500000) : 0.0), true});
    }
    if (bounded) {
        BoundArrivalsInRead(backlog, kPeriodS);
    }
    for (int j = 20; j <= 26; ++j) {
        stamp(j, backlog[static_cast<std::size_t>(j - 20)].arrival_s);
    }
    for (int j = 27; j < 40; ++j) {
        stamp(j, LineEnd(j) + 5e-5);
    }
    return errors;
}

TEST(ArrivalBounds, ABacklogReadAtOnceKeepsItsSweepSlots) {
    // Stamped with the read time, the first of the backlog looks 82 ms late: a later slot.
    const std::vector<double> raw = BacklogErrors(false);
    EXPECT_GT(raw[20], kPeriodS / 2);
    // Bounded: 7.44 ms per telegram of bytes after it, one period per telegram after it.
    const std::vector<double> e = BacklogErrors(true);
    for (std::size_t j = 0; j < e.size(); ++j) {
        EXPECT_GT(e[j], -1e-6) << "sweep " << j;  // 1 us: rounding at 1.8e9 s
        EXPECT_LT(e[j], 1e-4) << "sweep " << j;   // the 50 us envelope, in its own slot
    }
}

TEST(ArrivalBounds, OnlyMeasuredValuesFollowingEachOtherAreBounded) {
    // A reply between two stream telegrams may have delayed the second: no period bound across
    // it; the bytes-after bound is the caller's.
    std::vector<ReadTelegram> read{{10.0, true}, {10.001, false}, {10.02, true}, {10.03, true}};
    BoundArrivalsInRead(read, kPeriodS);
    EXPECT_DOUBLE_EQ(read[0].arrival_s, 10.0);
    EXPECT_DOUBLE_EQ(read[1].arrival_s, 10.001);
    EXPECT_DOUBLE_EQ(read[2].arrival_s, 10.03 - kPeriodS);
    EXPECT_DOUBLE_EQ(read[3].arrival_s, 10.03);
}

TEST(ArrivalBounds, ALateScanInTheWarmUpDoesNotMoveTheScansBefore) {
    // Sweeps 0..7 (the warm-up the driver holds back), 0.1 ms late except sweep 4: 8 ms, more
    // than the half period the warm-up allows, so the clock gives it slot 5 and the rest follow;
    // their residuals then move the phase a period back.
    ScanClock clock;
    std::vector<std::int64_t> k;
    std::vector<double> latest;
    for (int j = 0; j < 8; ++j) {
        latest.push_back(Latest(LineEnd(j) + (j == 4 ? 0.008 : 1e-4)));
        (void)clock.Stamp(latest.back());
        k.push_back(clock.last_index());
    }
    ASSERT_EQ(k[4], k[3] + 2);  // the case: the late scan skipped a slot
    const double phase_s = clock.phase_s();
    const auto error = [&](std::size_t j) {
        return phase_s + static_cast<double>(k[j]) * kPeriodS - Beam0(static_cast<int>(j));
    };
    EXPECT_NEAR(error(0), -kPeriodS, 1e-3);  // the clock's own slots: a period early
    EXPECT_NEAR(error(7), 1e-4, 1e-6);
    ScanClockConfig config;
    config.period_s = kPeriodS;
    ReslotHeldScans(k, latest, phase_s, config);
    for (std::size_t j = 0; j < k.size(); ++j) {
        EXPECT_EQ(k[j], k[0] + static_cast<std::int64_t>(j)) << "sweep " << j;
        EXPECT_GT(error(j), -1e-6) << "sweep " << j;
        EXPECT_LT(error(j), j == 4 ? 0.0081 : 1.1e-4) << "sweep " << j;  // its own latency
    }
}

TEST(ArrivalBounds, HeldScansAreNeverMovedEarlier) {
    // A phase later than the held scans' own stamps (the envelope left them out): their slots
    // stay the clock's, never earlier.
    std::vector<std::int64_t> k{0, 1, 2, 3};
    std::vector<double> latest;
    for (int j = 0; j < 4; ++j) {
        latest.push_back(Beam0(j) + 1e-4);
    }
    ReslotHeldScans(k, latest, Beam0(0) + 0.005, ScanClockConfig{});
    EXPECT_EQ(k, (std::vector<std::int64_t>{0, 1, 2, 3}));
}

}  // namespace
}  // namespace casmap::drivers
