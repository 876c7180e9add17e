// The driver talking to the virtual LMS 200 through a real pseudo-terminal.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <string>
#include <thread>

#include "casmap/core/input_error.hpp"
#include "casmap/drivers/lms200_driver.hpp"
#include "casmap/drivers/serial_port.hpp"
#include "casmap/drivers/virtual_lms200.hpp"
#include "test_source.hpp"

namespace casmap::drivers {
namespace {

using testing::NumberedSource;
using testing::SentLog;
using Clock = std::chrono::steady_clock;

std::string LinkPath(const std::string& name) {
    return "/tmp/casmap_drivers_test_" + std::to_string(getpid()) + "_" + name;
}

/// The scanner's scan as the driver must deliver it: same status, range and raw value.
void ExpectSameBeams(const core::Scan& got, const core::Scan& sent) {
    ASSERT_EQ(got.beams.size(), sent.beams.size());
    for (std::size_t i = 0; i < got.beams.size(); ++i) {
        EXPECT_EQ(got.beams[i].status, sent.beams[i].status) << "beam " << i;
        EXPECT_EQ(got.beams[i].raw, sent.beams[i].raw) << "beam " << i;
        if (sent.beams[i].status == core::BeamStatus::kOk) {
            EXPECT_EQ(got.beams[i].range_m, sent.beams[i].range_m) << "beam " << i;
        }
    }
}

/// Median of |x|: the stamp checks use it so that a test machine's scheduling hiccups (the
/// host reading late) do not decide them; without the correction it would be 14-35 ms.
double MedianAbs(std::vector<double> x) {
    for (double& v : x) {
        v = std::abs(v);
    }
    std::sort(x.begin(), x.end());
    return x.empty() ? 0.0 : x[x.size() / 2];
}

struct Recorded {
    std::vector<core::Scan> scans;
    std::vector<double> arrival_s;  // steady clock, for the rate
};

Recorded Record(Lms200Driver& driver, int count, double timeout_s) {
    Recorded r;
    const Clock::time_point start = Clock::now();
    while (static_cast<int>(r.scans.size()) < count) {
        std::optional<core::Scan> s = driver.NextScan(timeout_s);
        if (!s) {
            break;
        }
        r.scans.push_back(std::move(*s));
        r.arrival_s.push_back(std::chrono::duration<double>(Clock::now() - start).count());
    }
    return r;
}

TEST(ServeRecord, At38400EveryScanArrivesIntactAtTheLineRate) {
    NumberedSource source;
    VirtualLms200Config vc;
    vc.link_path = LinkPath("38400");
    VirtualLms200 scanner(vc, source);
    SentLog log;
    scanner.SetScanObserver([&log](const SentScan& s) { log.Record(s); });
    scanner.Start();

    DriverConfig dc;
    dc.device = vc.link_path;
    dc.baud = 38400;
    Lms200Driver driver(dc);
    driver.Connect();
    EXPECT_EQ(driver.info().baud, 38400);
    EXPECT_NE(driver.info().type.find("LMS200;30106"), std::string::npos);
    const Recorded r = Record(driver, 6, 2.0);
    ASSERT_EQ(r.scans.size(), 6U);
    std::vector<double> late_s;
    for (const core::Scan& s : r.scans) {
        const std::uint64_t index = s.beams[0].raw;
        ExpectSameBeams(s, NumberedSource::Make(index, Variant{}));
        // Latency correction: 96.9 ms on the line + 6.7 ms sweep taken off the arrival time.
        // The line is the bottleneck, so a completed sweep also waits up to one scan period
        // (13.3 ms) for the line, which no host can see: the stamp is late by up to that.
        late_s.push_back(s.stamp_s - log.Beam0(index));
    }
    std::sort(late_s.begin(), late_s.end());
    EXPECT_GT(late_s.front(), -0.004);
    EXPECT_LT(late_s[late_s.size() / 2], 1.0 / 75.0 + 0.004);  // median
    // 372-byte telegrams at 38400 baud: 96.9 ms each, so about 10.3 scans/s (not 75). Counted
    // in sweeps, not on this process's clock (which a loaded machine stalls): the scanner sends
    // the newest sweep whenever the line is free, 7.27 sweep periods after the last, so
    // consecutive scans are 7 or 8 sweeps apart (more only if the scanner's thread stalled).
    const double rate = 5.0 / (r.arrival_s[5] - r.arrival_s[0]);
    std::printf("38400 baud: %.2f scans/s as read\n", rate);
    std::vector<std::uint64_t> gaps;
    for (std::size_t i = 1; i < r.scans.size(); ++i) {
        gaps.push_back(r.scans[i].beams[0].raw - r.scans[i - 1].beams[0].raw);
        EXPECT_GE(gaps.back(), 7U) << "scan " << i;  // the line's rate: <= 10.3 scans/s
    }
    std::sort(gaps.begin(), gaps.end());
    EXPECT_LE(gaps[gaps.size() / 2], 8U);  // and the scanner keeps the line busy
    EXPECT_GT(scanner.stats().scans_skipped, 0U);
    const DriverCounters c = driver.counters();
    EXPECT_EQ(c.crc_errors, 0U);
    EXPECT_EQ(c.reconnects, 0U);
    // A telegram takes longer than a scan period: no phase information, arrival stamps.
    EXPECT_FALSE(driver.synchronised());
    driver.Close();
    // Close() returned the scanner to 9600 (its thread records that just after writing the
    // A0: allow it a moment on a loaded machine).
    for (int i = 0; i < 100 && scanner.stats().baud != 9600; ++i) {
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    EXPECT_EQ(scanner.stats().baud, 9600);
}

TEST(ServeRecord, At500000EverySweepArrivesIntact) {
    NumberedSource source;
    VirtualLms200Config vc;
    vc.link_path = LinkPath("500k");
    VirtualLms200 scanner(vc, source);
    SentLog log;
    scanner.SetScanObserver([&log](const SentScan& s) { log.Record(s); });
    scanner.Start();

    DriverConfig dc;
    dc.device = vc.link_path;
    dc.baud = 500000;
    dc.variant = Variant{180, 50};
    Lms200Driver driver(dc);
    driver.Connect();
    EXPECT_EQ(driver.info().variant, (Variant{180, 50}));
    const Recorded r = Record(driver, 20, 1.0);
    ASSERT_EQ(r.scans.size(), 20U);
    int consecutive = 0;
    std::vector<double> errors;
    for (std::size_t i = 0; i < r.scans.size(); ++i) {
        const std::uint64_t index = r.scans[i].beams[0].raw;
        ExpectSameBeams(r.scans[i], NumberedSource::Make(index, Variant{180, 50}));
        errors.push_back(r.scans[i].stamp_s - log.Beam0(index));
        if (i > 0 && index == r.scans[i - 1].beams[0].raw + 1U) {
            ++consecutive;
        }
    }
    // 732 bytes take 14.6 ms < 26.7 ms per 0.5-degree scan: the line carries every sweep
    // (counted in sweeps; the rate as read follows this process's stalls).
    const double rate = 19.0 / (r.arrival_s[19] - r.arrival_s[0]);
    std::printf("500000 baud, 0.5 deg: %.2f scans/s as read, %d of 19 consecutive\n", rate,
                consecutive);
    EXPECT_GE(consecutive, 14);
    // Latency correction (14.6 ms transmission + 20 ms interleaved sweep) applied, then the
    // scan clock: the line carries every sweep, so stamps go on the 26.7 ms sweep grid with
    // the phase of the least-late scan. Latency is one-sided, so no stamp is early by more
    // than the emulator's pacing granularity (one byte time, 20 us, plus rounding).
    EXPECT_TRUE(driver.synchronised());
    EXPECT_LT(MedianAbs(errors), 0.005);
    for (const double e : errors) {
        EXPECT_GT(e, -5e-5);
    }
    // The envelope only ever moves earlier here: the last stamp's phase is as good as the best
    // one's (1 us: a few roundings of stamps in seconds since 1970, 0.24 us each). Compared
    // modulo the period: a scan this process read more than 3/4 of a period late, with no
    // later one in the same read to bound it (a loaded machine), takes a later slot, the
    // one thing arrival times cannot tell (real-time indices can: Lms200Modes.RealTime...).
    const double period_s = 2.0 / 75.0;
    const double best = *std::min_element(errors.begin(), errors.end());
    const auto phase_of = [&](double e) {
        return e - std::round((e - best) / period_s) * period_s;
    };
    EXPECT_LT(phase_of(errors.back()), best + 1e-6);
    std::printf("500000 baud, 0.5 deg: last stamp error %.1f us\n", errors.back() * 1e6);
    EXPECT_EQ(driver.counters().crc_errors, 0U);
}

TEST(ServeRecord, FindsAScannerLeftAtAnotherRate) {
    NumberedSource source;
    VirtualLms200Config vc;
    vc.link_path = LinkPath("autodetect");
    VirtualLms200 scanner(vc, source);
    scanner.Start();
    {  // a previous client switched the scanner to 38400 and went away
        SerialPort port(vc.link_path, 9600);
        port.Write(EncodeTelegram(MakeBaudRequest(38400)), 1.0);
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    ASSERT_EQ(scanner.stats().baud, 38400);
    DriverConfig dc;
    dc.device = vc.link_path;
    dc.baud = 500000;
    Lms200Driver driver(dc);
    const Clock::time_point t0 = Clock::now();
    driver.Connect();  // silent at 9600 and 19200, answers the 0x32 probe at 38400
    EXPECT_LT(std::chrono::duration<double>(Clock::now() - t0).count(), 1.5);
    EXPECT_EQ(driver.info().baud, 500000);
    EXPECT_EQ(scanner.stats().baud, 500000);
    const std::optional<core::Scan> s = driver.NextScan(1.0);
    ASSERT_TRUE(s.has_value());
    ExpectSameBeams(*s, NumberedSource::Make(s->beams[0].raw, Variant{}));
}

TEST(ServeRecord, AStalledScannerThreadCatchesUpWithoutLasting) {
    NumberedSource source;
    VirtualLms200Config vc;
    vc.link_path = LinkPath("stall");
    VirtualLms200 scanner(vc, source);
    SentLog log;
    // Stall after the 4th and the 13th telegram sent (whatever sweeps they carry: on a loaded
    // machine the scanner may already have skipped one): 20 ms and 80 ms, within and beyond
    // the 50 ms catch-up.
    std::atomic<int> sent{0};
    std::atomic<std::uint64_t> first_stall{0};
    std::atomic<std::uint64_t> second_stall{0};
    scanner.SetScanObserver([&](const SentScan& s) {
        log.Record(s);
        const int n = ++sent;
        if (n == 4 || n == 13) {
            (n == 4 ? first_stall : second_stall) = s.index;
            std::this_thread::sleep_for(std::chrono::milliseconds(n == 4 ? 20 : 80));
        }
    });
    scanner.Start();
    DriverConfig dc;
    dc.device = vc.link_path;
    dc.baud = 500000;
    // Arrival stamps (arrival - transmission - sweep): each scan's own latency, which is
    // what the line's schedule decides (the scan clock would also move stamps between slots).
    dc.stamps = StampMode::kArrival;
    Lms200Driver driver(dc);
    driver.Connect();
    const Recorded r = Record(driver, 30, 1.0);
    ASSERT_EQ(r.scans.size(), 30U);
    ASSERT_GT(second_stall.load(), first_stall.load());
    std::vector<double> between;  // after the 20 ms stall, before the 80 ms one
    std::vector<double> after;
    for (std::size_t i = 0; i < r.scans.size(); ++i) {
        const std::uint64_t index = r.scans[i].beams[0].raw;
        const double error_s = r.scans[i].stamp_s - log.Beam0(index);
        if (index >= first_stall + 4 && index <= second_stall) {
            between.push_back(error_s);
        } else if (index >= second_stall + 8) {
            after.push_back(error_s);
        }
    }
    // A few telegrams after each stall the line is on the mirror's schedule again: a lasting
    // lag would leave every later telegram about 20 ms late or more. This process's own
    // latency only ever adds, so the least late of each set tells, against half that lag:
    // 10 ms (two busy loops on two cores keep even the least late of ten telegrams 4-5.4 ms
    // late: every wake-up waits for a time slice). No telegram is early (beyond the
    // emulator's 20 us byte-time pacing and rounding).
    ASSERT_FALSE(between.empty());
    ASSERT_FALSE(after.empty());
    EXPECT_LT(*std::min_element(between.begin(), between.end()), 0.010);
    EXPECT_LT(*std::min_element(after.begin(), after.end()), 0.010);
    for (const std::vector<double>* set : {&between, &after}) {
        EXPECT_GT(*std::min_element(set->begin(), set->end()), -5e-5);
    }
}

TEST(ServeRecord, FaultsAreRejectedAndCountedAndTheDriverRecovers) {
    NumberedSource source;
    VirtualLms200Config vc;
    vc.link_path = LinkPath("faults");
    vc.faults = ParseFaults("crc=0.04,garbage=0.04,drop=0.04,disconnect=0.6");
    vc.faults.offline_s = 0.15;
    vc.faults.seed = 4242;
    std::printf("fault seed %llu\n", static_cast<unsigned long long>(vc.faults.seed));
    VirtualLms200 scanner(vc, source);
    SentLog log;
    scanner.SetScanObserver([&log](const SentScan& s) { log.Record(s); });
    scanner.Start();

    DriverConfig dc;
    dc.device = vc.link_path;
    dc.baud = 500000;
    Lms200Driver driver(dc);
    // A disconnect may hit the handshake itself (every 0.6 s; Connect takes 0.2-0.5 s on a
    // loaded machine), or come just before it, while the device is away ("cannot open"): try
    // again, as casmap record does.
    for (int attempt = 0;; ++attempt) {
        try {
            driver.Connect();
            break;
        } catch (const SerialError&) {
            ASSERT_LT(attempt, 20) << "never connected";
        } catch (const InputError& e) {
            ASSERT_NE(std::string(e.what()).find("cannot open"), std::string::npos) << e.what();
            ASSERT_LT(attempt, 20) << "never connected";
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    std::set<std::uint64_t> received;
    const Clock::time_point end = Clock::now() + std::chrono::milliseconds(1500);
    while (Clock::now() < end) {
        std::optional<core::Scan> s = driver.NextScan(1.0);
        if (!s) {
            continue;
        }
        const std::uint64_t index = s->beams[0].raw;
        ExpectSameBeams(*s, NumberedSource::Make(index, Variant{}));
        EXPECT_TRUE(received.insert(index).second) << "scan " << index << " twice";
    }
    driver.Close();
    scanner.Stop();
    const VirtualLms200Stats st = scanner.stats();
    const DriverCounters c = driver.counters();
    std::printf(
        "sent intact %zu damaged %zu received %zu | faults crc %llu drop %llu garbage %llu "
        "disconnects %llu | driver crc %llu bad_headers %llu dropped "
        "%llu resyncs %llu "
        "reconnects %llu\n",
        log.intact.size(), log.damaged.size(), received.size(),
        static_cast<unsigned long long>(st.crc_faults),
        static_cast<unsigned long long>(st.drop_faults),
        static_cast<unsigned long long>(st.garbage_faults),
        static_cast<unsigned long long>(st.disconnects),
        static_cast<unsigned long long>(c.crc_errors),
        static_cast<unsigned long long>(c.bad_headers),
        static_cast<unsigned long long>(c.dropped_bytes),
        static_cast<unsigned long long>(c.resyncs), static_cast<unsigned long long>(c.reconnects));
    // No damaged telegram accepted. An intact one is lost only when garbage followed it
    // before the line went idle (the follower check cannot tell that from a damaged frame
    // whose CRC matched by chance): each such loss is a bad follower, at most one per
    // garbage fault. Scans that went out after the last NextScan (while Close() stops the
    // stream) are flushed by design.
    for (const std::uint64_t i : received) {
        EXPECT_TRUE(log.intact.count(i) == 1) << "scan " << i << " was not sent intact";
    }
    ASSERT_FALSE(received.empty());
    const std::uint64_t last = *received.rbegin();
    // Of each connection, the scans sent after the last one received (all, if none was)
    // were still in the pty or on their way when the device vanished, lost with it: a reader
    // stalled longer than the scanner's 0.1 s wait (a loaded machine) loses a whole pty
    // buffer of them.
    std::map<std::uint64_t, std::uint64_t> last_received;  // per connection
    for (const std::uint64_t i : received) {
        std::uint64_t& l = last_received[log.connection.at(i)];
        l = std::max(l, i);
    }
    std::uint64_t lost = 0;
    std::uint64_t cut_off = 0;
    for (const std::uint64_t i : log.intact) {
        const auto l = last_received.find(log.connection.at(i));
        if (i < last && received.count(i) == 0 && (l == last_received.end() || i > l->second)) {
            ++cut_off;
        } else if (i < last && received.count(i) == 0) {
            ++lost;
            std::printf("intact scan %llu lost (damaged neighbours: %d %d)\n",
                        static_cast<unsigned long long>(i),
                        static_cast<int>(log.damaged.count(i - 1)),
                        static_cast<int>(log.damaged.count(i + 1)));
        }
    }
    std::printf("bad followers %llu malformed %llu cut off by a disconnect %llu\n",
                static_cast<unsigned long long>(c.bad_followers),
                static_cast<unsigned long long>(c.malformed),
                static_cast<unsigned long long>(cut_off));
    // Every other lost scan is one rejected for a bad follower.
    EXPECT_LE(lost, c.bad_followers);
    EXPECT_LE(c.bad_followers, st.garbage_faults + st.drop_faults);
    EXPECT_GT(st.crc_faults + st.drop_faults, 0U);
    EXPECT_GT(st.garbage_bytes, 0U);
    EXPECT_GE(st.disconnects, 2U);
    // Damaged telegrams were never accepted (checked above) and are counted: a flipped bit is
    // always a CRC error (unless the telegram was cut by a disconnect); a dropped byte is a
    // CRC error, a bad header or, if it was the STX, stray bytes (dropped_bytes, resyncs).
    EXPECT_GE(static_cast<std::int64_t>(c.crc_errors),
              static_cast<std::int64_t>(st.crc_faults) - static_cast<std::int64_t>(st.disconnects));
    EXPECT_GE(c.resyncs, 1U);
    EXPECT_GE(c.dropped_bytes, st.garbage_bytes);
    EXPECT_GE(c.reconnects, 1U);
    EXPECT_GT(received.size(), 20U);
}

}  // namespace
}  // namespace casmap::drivers
