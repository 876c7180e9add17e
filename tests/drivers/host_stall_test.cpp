// A client stalled across a disconnect of the virtual scanner (forced by the test: it does
// not read until the device has vanished, so the outcome does not depend on the machine's
// load): it loses only the scans it had not read, which SentScan::connection identifies.
// (What the driver's stamps do when the host stalls is tested on synthetic arrivals in
// arrival_bounds_test.cpp.)
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
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

std::string LinkPath(const std::string& name) {
    return "/tmp/casmap_host_stall_test_" + std::to_string(getpid()) + "_" + name;
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
    EXPECT_GE(after, 1U);
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
