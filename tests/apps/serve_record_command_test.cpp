// `casmap serve --run` and `casmap record` as processes talking through a pseudo-terminal:
// every recorded scan equals the served one value for value, the JSON line is complete, every
// streaming mode records, a scanner that appears late is waited for, and bad input ends with
// exit 2 and no run file (serve_record_map_test.cpp maps a recorded run).
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <string>
#include <thread>

#include "casmap/core/lms200.hpp"
#include "casmap/io/run_file.hpp"
#include "tests/apps/cli_runner.hpp"
#include "tests/apps/serve_fixture.hpp"

namespace casmap {
namespace {
namespace fs = std::filesystem;

using test::Casmap;
using test::Result;
using test::ServeRecordCommand;

/// A run of `count` 181-beam scans in mm; beam 0 of scan i holds i mm, so scans name themselves.
io::RunData NumberedRun(int count) {
    io::RunData run;
    const core::Lms200Format mm{};
    for (int i = 0; i < count; ++i) {
        core::Scan s;
        s.stamp_s = i / 75.0;
        s.start_angle_rad = -std::numbers::pi / 2;
        s.angle_step_rad = std::numbers::pi / 180.0;
        s.beam_period_s = (1.0 / 75.0) / 360.0;
        s.beams.resize(181);
        for (int b = 0; b < 181; ++b) {
            const auto raw = static_cast<std::uint16_t>(b == 0 ? i : (i * 37 + b * 101) % 8190);
            s.beams[static_cast<std::size_t>(b)] = mm.Decode(raw);
        }
        run.scans.push_back(s);
    }
    run.format = mm;
    return run;
}

constexpr double kDeg = std::numbers::pi / 180.0;

TEST_F(ServeRecordCommand, RecordedScansEqualTheServedOnes) {
    const io::RunData served = NumberedRun(200);
    io::WriteRunFile(dir_ / "served.h5", served);
    const fs::path link = dir_ / "lms";
    StartServe({"--run", (dir_ / "served.h5").string(), "--link", link.string()});
    ASSERT_TRUE(WaitForLink(link));
    const fs::path out = dir_ / "rec.h5";
    const Result r = Casmap("record --device " + link.string() +
                            " --baud 500000 --scans 30 --timeout 5 --out " + out.string());
    ASSERT_EQ(r.code, 0) << r.output;
    for (const char* key : {"\"scans\": 30", "\"bytes\": ", "\"crc_errors\": 0",
                            "\"resyncs\": ", "\"reconnects\": 0", "\"scans_per_second\": "}) {
        EXPECT_NE(r.output.find(key), std::string::npos) << key << " in " << r.output;
    }
    const io::RunData rec = io::ReadRunFile(out);
    ASSERT_EQ(rec.scans.size(), 30U);
    ASSERT_TRUE(rec.format.has_value());
    for (const core::Scan& s : rec.scans) {
        const std::size_t index = s.beams.at(0).raw;
        ASSERT_LT(index, served.scans.size());
        const core::Scan& want = served.scans[index];
        for (std::size_t b = 0; b < s.beams.size(); ++b) {
            EXPECT_EQ(s.beams[b].raw, want.beams[b].raw) << "scan " << index << " beam " << b;
            EXPECT_EQ(s.beams[b].status, want.beams[b].status);
        }
        EXPECT_NEAR(s.angle_step_rad, want.angle_step_rad, 1e-12);
    }
}

TEST_F(ServeRecordCommand, BadInputIsExitTwoWithoutARunFile) {
    const fs::path out = dir_ / "rec.h5";
    // An absent device is retried with back-off until --timeout, then named.
    Result r = Casmap("record --device /nonexistent/ttyX --timeout 1 --out " + out.string());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("/nonexistent/ttyX"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("attempts"), std::string::npos) << r.output;
    r = Casmap("record --device /dev/null --out " + out.string());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("not a terminal"), std::string::npos) << r.output;
    r = Casmap("record --device /dev/null --baud 57600 --out " + out.string());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("--baud = 57600"), std::string::npos) << r.output;
    r = Casmap("serve --run " + (dir_ / "missing.h5").string());
    EXPECT_EQ(r.code, 2) << r.output;
    r = Casmap("serve --run x.h5 --faults crc=7");
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("crc"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(out));
}

// Issue #13 item 2: every input is checked before connecting (no device is needed to see
// these errors, and they come at once even with a long --timeout).
TEST_F(ServeRecordCommand, RecordChecksItsInputsBeforeConnecting) {
    const std::string device = " --device /nonexistent/ttyX --timeout 60";
    const auto started = std::chrono::steady_clock::now();
    Result r = Casmap("record" + device + " --out " + (dir_ / "missing" / "rec.h5").string());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("--out"), std::string::npos) << r.output;
    r = Casmap("record" + device + " --out " + dir_.string());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("is a folder"), std::string::npos) << r.output;
    r = Casmap("record" + device + " --poses " + dir_.string() + " --out " +
               (dir_ / "rec.h5").string());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("--poses"), std::string::npos) << r.output;
    r = Casmap("record" + device + " --poses " + (dir_ / "nodir" / "p.txt").string() + " --out " +
               (dir_ / "rec.h5").string());
    EXPECT_EQ(r.code, 2) << r.output;
    r = Casmap("record" + device + " --mode mean:1 --out " + (dir_ / "rec.h5").string());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("mean scans"), std::string::npos) << r.output;
    r = Casmap("record" + device + " --mode fast --out " + (dir_ / "rec.h5").string());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("--mode"), std::string::npos) << r.output;
    r = Casmap("record" + device + " --scans 0 --out " + (dir_ / "rec.h5").string());
    EXPECT_NE(r.code, 0) << r.output;
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(),
              30.0);
    EXPECT_FALSE(fs::exists(dir_ / "rec.h5"));
}

// Issue #13 item 1: --poses-out into a missing folder is refused before serving, and no
// --link symlink is left behind.
TEST_F(ServeRecordCommand, ServeRefusesAPoseFileItCannotWrite) {
    io::WriteRunFile(dir_ / "served.h5", NumberedRun(20));
    const fs::path link = dir_ / "lms";
    const Result r =
        Casmap("serve --run " + (dir_ / "served.h5").string() + " --link " + link.string() +
               " --poses-out " + (dir_ / "missing" / "poses.txt").string());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("--poses-out"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(fs::symlink_status(link)));
}

// Issue #13 item 8: a device absent at start is waited for (retry with back-off).
TEST_F(ServeRecordCommand, RecordWaitsForAScannerThatAppearsLater) {
    io::WriteRunFile(dir_ / "served.h5", NumberedRun(400));
    const fs::path link = dir_ / "lms";
    const fs::path out = dir_ / "rec.h5";
    std::thread late([&] {
        std::this_thread::sleep_for(std::chrono::milliseconds(1500));
        StartServe({"--run", (dir_ / "served.h5").string(), "--link", link.string()});
    });
    const Result r = Casmap("record --device " + link.string() +
                            " --baud 500000 --scans 10 --timeout 20 --out " + out.string());
    late.join();
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(r.output.find("\"connect_attempts\": 1,"), std::string::npos) << r.output;
    EXPECT_EQ(io::ReadRunFile(out).scans.size(), 10U);
}

// Every streaming mode through the CLI: partial scans of 0.5 deg are joined into complete
// scans equal to the served ones; sub-ranges carry their beams; mean values one beam mean.
TEST_F(ServeRecordCommand, RecordAcceptsEveryStreamingMode) {
    io::RunData served = NumberedRun(600);
    for (core::Scan& s : served.scans) {  // 0.5 deg: 361 beams
        s.angle_step_rad = 0.5 * kDeg;
        s.beam_period_s = (1.0 / 75.0) / 720.0;
        s.beams.resize(361, s.beams.back());
    }
    io::WriteRunFile(dir_ / "served.h5", served);
    const fs::path link = dir_ / "lms";
    StartServe({"--run", (dir_ / "served.h5").string(), "--link", link.string()});
    ASSERT_TRUE(WaitForLink(link));
    struct Case {
        std::string mode;
        std::size_t beams;
        double start_deg;
    };
    for (const Case& c : {Case{"partial", 361, -90.0}, Case{"subrange:21-60", 40, -80.0},
                          Case{"mean:2", 361, -90.0}, Case{"mean-subrange:2:1-10", 10, -90.0}}) {
        const fs::path out = dir_ / "rec.h5";
        const Result r = Casmap("record --device " + link.string() +
                                " --baud 500000 --scans 6 --timeout 10 --mode " + c.mode +
                                " --out " + out.string());
        ASSERT_EQ(r.code, 0) << c.mode << ": " << r.output;
        const io::RunData rec = io::ReadRunFile(out);
        ASSERT_EQ(rec.scans.size(), 6U) << c.mode;
        for (const core::Scan& s : rec.scans) {
            ASSERT_EQ(s.beams.size(), c.beams) << c.mode;
            EXPECT_NEAR(s.start_angle_rad, c.start_deg * kDeg, 1e-9) << c.mode;
            if (c.mode == "partial") {  // complete scans, value for value
                const core::Scan& want = served.scans.at(s.beams[0].raw);
                for (std::size_t b = 0; b < s.beams.size(); ++b) {
                    EXPECT_EQ(s.beams[b].raw, want.beams[b].raw) << "beam " << b;
                }
            }
        }
        EXPECT_NE(r.output.find("\"malformed\": 0"), std::string::npos) << r.output;
        fs::remove(out);
    }
}

}  // namespace
}  // namespace casmap
