// The driver's stamps when the host or the scanner's thread stalls, forced here by the test
// (far longer than a machine's scheduling noise, so the outcome does not depend on load): a
// backlog read at once keeps every scan in its sweep slot, a late scan during the scan
// clock's warm-up does not move the scans before it, and a client stalled across a
// disconnect loses only the scans it had not read (each telegram carries its connection).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <set>
#include <thread>

#include "casmap/drivers/lms200_driver.hpp"
#include "casmap/drivers/virtual_lms200.hpp"
#include "test_source.hpp"

namespace casmap::drivers {
namespace {

using testing::NumberedSource;
using testing::SentLog;
using Clock = std::chrono::steady_clock;

std::string LinkPath(const std::string& name) {
    return "/tmp/casmap_host_stall_test_" + std::to_string(getpid()) + "_" + name;
}

/// Stamp error (stamp - when beam 0 was measured) of each scan, in s.
std::vector<double> Errors(const std::vector<core::Scan>& scans, SentLog& log) {
    std::vector<double> e;
    for (const core::Scan& s : scans) {
        e.push_back(s.stamp_s - log.Beam0(s.beams[0].raw));
    }
    return e;
}

/// Every scan in its own sweep slot: never early (beyond the emulator's 20 us byte pacing and
/// rounding), less than half a period late (a scan in the next slot is a period late).
void ExpectOwnSlots(const std::vector<double>& errors, double period_s, const char* what) {
    for (std::size_t i = 0; i < errors.size(); ++i) {
        EXPECT_GT(errors[i], -5e-5) << what << " scan " << i;
        EXPECT_LT(errors[i], period_s / 2) << what << " scan " << i;
    }
}

TEST(HostStall, ABacklogReadAtOnceKeepsItsSweepSlots) {
    NumberedSource source;
    VirtualLms200Config vc;
    vc.link_path = LinkPath("backlog");
    VirtualLms200 scanner(vc, source);
    SentLog log;
    scanner.SetScanObserver([&log](const SentScan& s) { log.Record(s); });
    scanner.Start();
    DriverConfig dc;
    dc.device = vc.link_path;
    dc.baud = 500000;
    // 0.5 degree: a scan every 26.7 ms, so that the last scan of the backlog keeps its slot
    // even when this machine delays the scanner's thread or this one by up to 20 ms.
    dc.variant = Variant{180, 50};
    Lms200Driver driver(dc);
    driver.Connect();
    std::vector<core::Scan> scans;
    const auto read = [&](int count) {
        for (int i = 0; i < count; ++i) {
            std::optional<core::Scan> s = driver.NextScan(1.0);
            ASSERT_TRUE(s.has_value());
            scans.push_back(std::move(*s));
        }
    };
    read(12);  // past the warm-up
    // This process stalls for 100 ms: 3-4 telegrams of 732 bytes wait in the pty and are read
    // at once, all with the same read time. Stamped with it, the first would look 80 ms late
    // and land 3 slots on; each is bounded by the one after it (one period per telegram).
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    read(12);
    const std::vector<double> e = Errors(scans, log);
    ExpectOwnSlots(e, 2.0 / 75.0, "backlog");
    for (std::size_t i = 1; i < scans.size(); ++i) {  // nothing lost, nothing skipped
        EXPECT_EQ(scans[i].beams[0].raw, scans[i - 1].beams[0].raw + 1) << "scan " << i;
    }
    EXPECT_TRUE(driver.synchronised());
}

TEST(HostStall, ALateScanInTheWarmUpDoesNotMoveTheScansBefore) {
    NumberedSource source;
    VirtualLms200Config vc;
    vc.link_path = LinkPath("warmup");
    VirtualLms200 scanner(vc, source);
    SentLog log;
    // The scanner's thread stalls 25 ms after its 3rd telegram: the 4th, due 20.7 ms after the
    // 3rd sweep ended, goes out 11.7 ms late, more than the half period the warm-up allows,
    // so the clock first gives it the next slot.
    std::atomic<int> sent{0};
    scanner.SetScanObserver([&](const SentScan& s) {
        log.Record(s);
        if (++sent == 3) {
            std::this_thread::sleep_for(std::chrono::milliseconds(25));
        }
    });
    scanner.Start();
    DriverConfig dc;
    dc.device = vc.link_path;
    dc.baud = 500000;
    Lms200Driver driver(dc);
    driver.Connect();
    std::vector<core::Scan> scans;
    for (int i = 0; i < 12; ++i) {
        std::optional<core::Scan> s = driver.NextScan(1.0);
        ASSERT_TRUE(s.has_value());
        scans.push_back(std::move(*s));
    }
    // The first 8 were held for the envelope; the ones before the late scan came out a period
    // early when only the clock's first slots were used.
    ExpectOwnSlots(Errors(scans, log), 1.0 / 75.0, "warm-up");
}

TEST(HostStall, AClientStalledAcrossADisconnectLosesOnlyWhatWasUnread) {
    NumberedSource source;
    VirtualLms200Config vc;
    vc.link_path = LinkPath("unread");
    vc.faults.disconnect_period_s = 1.5;
    vc.faults.offline_s = 0.2;
    VirtualLms200 scanner(vc, source);
    SentLog log;
    scanner.SetScanObserver([&log](const SentScan& s) { log.Record(s); });
    scanner.Start();
    DriverConfig dc;
    dc.device = vc.link_path;
    dc.baud = 500000;
    Lms200Driver driver(dc);
    driver.Connect();
    std::set<std::uint64_t> received;
    for (int i = 0; i < 5; ++i) {
        std::optional<core::Scan> s = driver.NextScan(1.0);
        ASSERT_TRUE(s.has_value());
        received.insert(s->beams[0].raw);
    }
    // Not reading until the device has vanished: what the pty holds then is lost with it.
    while (scanner.stats().disconnects == 0) {
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    for (int i = 0; i < 10; ++i) {
        if (std::optional<core::Scan> s = driver.NextScan(3.0)) {
            received.insert(s->beams[0].raw);
        }
    }
    driver.Close();
    scanner.Stop();
    std::lock_guard lock(log.mutex);
    std::uint64_t last_before = 0;  // the last scan of the first connection received
    std::size_t after = 0;
    for (const std::uint64_t i : received) {
        ASSERT_EQ(log.intact.count(i), 1U) << "scan " << i;
        if (log.connection.at(i) == 0) {
            last_before = std::max(last_before, i);
        } else {
            ++after;
        }
    }
    // The driver reconnected and streams again; of the first connection it lost only scans
    // after the last one it read (they were in the pty when it vanished), none before.
    EXPECT_GE(after, 5U);
    std::uint64_t cut_off = 0;
    for (const std::uint64_t i : log.intact) {
        if (log.connection.at(i) == 0 && received.count(i) == 0) {
            EXPECT_GT(i, last_before) << "scan " << i << " lost before the stall";
            ++cut_off;
        }
    }
    std::printf("first connection: %llu scans cut off by the disconnect\n",
                static_cast<unsigned long long>(cut_off));
    EXPECT_GE(cut_off, 1U);
}

}  // namespace
}  // namespace casmap::drivers
