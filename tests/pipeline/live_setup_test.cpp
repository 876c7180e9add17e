// pipeline::MakeLiveSetup (what `casmap live` runs before RunLive), device half: the options
// reach the session's configuration, errors name the options' fields (never a flag), and a
// setup on a virtual LMS 200 with a pose file maps what the scanner sends.
#include "casmap/pipeline/live_setup.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include "../drivers/test_source.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/core/trajectory.hpp"
#include "casmap/drivers/pose_file.hpp"
#include "casmap/drivers/virtual_lms200.hpp"
#include "casmap/io/atomic_file.hpp"
#include "casmap/io/run_file.hpp"
#include "tests/input_error_of.hpp"
#include "tests/temp_dir.hpp"

namespace casmap::pipeline {
namespace {
namespace fs = std::filesystem;

/// The error MakeLiveSetup throws for `o` (its field), checking that no flag is named.
std::string FieldOfError(const LiveOptions& o) {
    try {
        (void)MakeLiveSetup(o, 1);
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()).find("--"), std::string::npos) << e.what();
        return e.field();
    }
    return "(no error)";
}

LiveOptions DeviceOptions(const std::string& device) {
    static const fs::path dir = casmap::test::MakeTempDir("live_setup");
    LiveOptions o;
    o.device = device;
    o.poses = (dir / "casmap_live_setup_poses.txt").string();
    o.out = (dir / "casmap_live_setup_out").string();
    return o;
}

TEST(LiveSetup, DeviceOptionsReachTheConfiguration) {
    LiveOptions o = DeviceOptions("/dev/null");  // nothing connects before RunLive
    o.window_rows = 55;
    o.window_cols = 200;
    o.m = 45;
    o.obstacle_cell_m = 0.2;
    o.snapshot_every_s = 0.5;
    o.scans = 7;
    o.timeout_s = 3.0;
    o.pose_tolerance_s = 0.1;
    o.cas = {"A=30", "cell_m=0.05", "a=2"};
    const LiveSetup s = MakeLiveSetup(o, 1);
    EXPECT_EQ(s.config.window.rows, 55);
    EXPECT_EQ(s.config.window.cols, 200);
    EXPECT_EQ(s.config.window.m, 45);
    EXPECT_EQ(s.config.window.obstacle_cell_m, 0.2);
    EXPECT_EQ(s.config.window.cas.A, 30.0);
    EXPECT_EQ(s.config.window.cell_m, 0.05);  // the window maps on the filter's cell
    EXPECT_EQ(s.config.window.a, 2);
    EXPECT_EQ(s.config.window.origin_x_m, 0.0);  // a device: no simulated map to align with
    EXPECT_EQ(s.config.snapshot_every_s, 0.5);
    EXPECT_EQ(s.config.max_scans, 7U);
    EXPECT_EQ(s.config.timeout_s, 3.0);
    EXPECT_EQ(s.config.pose_tolerance_s, 0.1);
    EXPECT_EQ(s.config.out_dir, fs::path(o.out));
    ASSERT_NE(s.scans, nullptr);
    ASSERT_NE(s.poses, nullptr);
    EXPECT_NE(s.scans->name().find("/dev/null"), std::string::npos) << s.scans->name();
    EXPECT_EQ(s.poses->name(), o.poses);
    LiveOptions d = DeviceOptions("/dev/null");
    EXPECT_EQ(MakeLiveSetup(d, 1).config.window.m, mapper::ActiveWindowConfig{}.m);
}

TEST(LiveSetup, ErrorsNameTheOptionsFields) {
    LiveOptions o;
    o.out = "out";
    EXPECT_EQ(FieldOfError(o), "device / scene");  // neither source
    o = DeviceOptions("/dev/null");
    o.scene = "course.yaml";
    EXPECT_EQ(FieldOfError(o), "device / scene");  // both
    o = DeviceOptions("/dev/null");
    o.poses.clear();
    EXPECT_EQ(FieldOfError(o), "poses / poses_socket");
    o = DeviceOptions("/dev/null");
    o.poses_socket = "udp:0";
    EXPECT_EQ(FieldOfError(o), "poses / poses_socket");
    o = DeviceOptions("/dev/null");
    o.baud = 7;
    EXPECT_EQ(FieldOfError(o), "baud");
    o = DeviceOptions("/dev/null");
    o.m = 500;  // beyond the window's 200 rows
    EXPECT_EQ(FieldOfError(o), "m");
    o = DeviceOptions("/dev/null");
    o.snapshot_every_s = -1.0;
    EXPECT_EQ(FieldOfError(o), "snapshot_every_s");
    o = DeviceOptions("/dev/null");
    o.cas = {"k=9"};
    EXPECT_EQ(FieldOfError(o), "k");
    o = LiveOptions{};
    o.scene = "course.yaml";
    EXPECT_EQ(FieldOfError(o), "scene / motion");
}

TEST(LiveSetup, MapsAVirtualScannerWithAPoseFile) {
    drivers::testing::NumberedSource source;
    drivers::VirtualLms200Config vc;
    vc.link_path = "/tmp/casmap_live_setup_" + std::to_string(getpid());
    drivers::VirtualLms200 scanner(vc, source);
    scanner.Start();
    // Poses in the scans' clock (the system clock), every 10 ms from now - 5 s to now + 60 s.
    const double now =
        std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
    std::vector<core::TimedPose> samples;
    for (int i = 0; i <= 6500; ++i) {
        core::TimedPose p;
        p.stamp_s = now - 5.0 + i * 0.01;
        p.world_T_sensor.translation = {0.001 * i, 0.0, 0.6};
        samples.push_back(p);
    }
    LiveOptions o = DeviceOptions(vc.link_path);
    fs::remove_all(o.out);
    io::WriteTextAtomically(o.poses, drivers::PoseFileText(core::Trajectory(samples)));
    o.window_rows = 55;
    o.m = 45;
    o.snapshot_every_s = 0.0;
    o.scans = 3;
    o.timeout_s = 20.0;
    LiveSetup s = MakeLiveSetup(o, 1);
    const std::atomic<bool> stop{false};
    const LiveResult r = RunLive(s.config, *s.scans, *s.poses, stop, {});
    scanner.Stop();
    EXPECT_FALSE(r.timed_out);
    EXPECT_EQ(r.status.scans, 3U);
    EXPECT_EQ(r.status.scans_mapped, 3U);
    EXPECT_EQ(r.status.dropped, 0U);
    EXPECT_EQ(io::ReadRunFile(r.run_file).scans.size(), 3U);
    const std::string json = LiveSummaryJson(r);
    EXPECT_NE(json.find("\"scans\": 3, \"scans_mapped\": 3, \"dropped\": 0"), std::string::npos)
        << json;
}

TEST(LiveSetup, WindowSizeIsTwoIntegers) {
    LiveOptions o;
    ParseWindowSize("120,300", o);
    EXPECT_EQ(o.window_rows, 120);
    EXPECT_EQ(o.window_cols, 300);
    ParseWindowSize("80,90,", o);  // a trailing separator ends a list (core::SplitList)
    EXPECT_EQ(o.window_cols, 90);
    for (const char* bad : {"120", "120,x", "1.5,2", "1,2,3", ""}) {
        EXPECT_EQ(test::ErrorOf([&] { ParseWindowSize(bad, o); }),
                  std::string("window") + (*bad == 0 ? "" : std::string(" = ") + bad) +
                      " (R,C: two integers (rows, columns))")
            << bad;
    }
}

TEST(LiveSetup, TimeoutMessageSaysWhatWasKept) {
    LiveResult r;
    EXPECT_EQ(LiveTimeoutMessage(r, "/dev/x", 2.5), "/dev/x: no scan for 2.5 s; nothing received");
    r.status.scans = 4;
    r.run_file = "out/run.h5";
    EXPECT_EQ(LiveTimeoutMessage(r, "/dev/x", 2.0),
              "/dev/x: no scan for 2 s; wrote the 4 scans received to out/run.h5");
}

}  // namespace
}  // namespace casmap::pipeline
